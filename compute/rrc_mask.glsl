// The mask (RRC_MASK_*) and where a pass reads classify's from: the image
// classify wrote (u_mask, read in place) or the library's copy of it bound
// through a sampler (s_classified: the storage images are at lavapipe's 64 a
// stage).  Shared by the per-pixel passes, the list and copy-out.
#ifndef RRC_MASK_GLSL
#define RRC_MASK_GLSL

#include "rrc_values.glsl"  // bindings, spec ids
#include "rrc_io.glsl"      // RRC_LOAD

// Classify's mask is in u_mask (the image classify wrote: storage loads,
// cheaper than the sampler of s_classified on lavapipe), else in s_classified.
layout(constant_id = RRC_SPEC_MASK_IN_PLACE) const bool MASK_IN_PLACE = false;
uint rrc_classified(ivec2 px) { return RRC_LOAD(1u, 1u, MASK_IN_PLACE ? imageLoad(u_mask, px).r : texelFetch(s_classified, px, 0).r); }

#endif
