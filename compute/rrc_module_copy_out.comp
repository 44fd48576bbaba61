// The copy-out pass (docs/design/frame-plan.md): after
// RESOLVE_LISTED, the library's results into the host's images.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "rrc_values.glsl"  // RRC_MAX_CHANNELS, RRC_MASK_*, spec ids, bindings

layout(local_size_x_id = RRC_SPEC_GROUP_SIZE_X, local_size_y_id = RRC_SPEC_GROUP_SIZE_Y) in;

// This pass's bindings, exactly (rrc_module_bindings.h; the library's layout is made from the same list).
#include "rrc_bindings.glsl"
RRC_MODULE_COPY_OUT_BINDINGS(RRC_DECLARE)

#include "rrc_depth.glsl"  // u_prev_depth (its size), rrc_store
#include "rrc_channel_slots.glsl"
#include "rrc_mask.glsl"

// COPY_OUT: also copy classify's mask into u_mask (the host's).
layout(constant_id = RRC_SPEC_COPY_MASK) const bool COPY_MASK = false;

// COPY_OUT, one channel slot: its history value and age at px into the
// host's output and age images.  One function a slot (storage-image arrays
// are indexed by constants), emitted by RRC_COPY_OUT_SLOT.  Each store tests
// its constant first: `store && constant` specialises to a select that
// spirv-opt does not fold (tests/spirv would see a cost).
#define RRC_COPY_OUT_SLOT(C)                                                                                            \
    void rrc_copy_out_##C(ivec2 px, bool store) {                                                                       \
        if (C >= CH_COUNT) return;                                                                                      \
        const bool FP16 = CH##C##_precision; /* the precision field is on for an fp16 history */                     \
        const bool ONE = !CH##C##_components;                                                                          \
        const bool PACKED = FP16 && ONE;                                                                                \
        uint word = PACKED ? imageLoad(u_hist_packed[C], px).r : 0u;                                                    \
        vec4 v = PACKED ? vec4(unpackHalf2x16(word).x, 0.0, 0.0, 0.0)                                                  \
                 : FP16 ? imageLoad(u_hist_rgba16f[C], px)                                                              \
                 : (ONE ? imageLoad(u_hist_r32f[C], px) : imageLoad(u_hist_rgba32f[C], px));                            \
        if (ONE) v = vec4(v.x, 0.0, 0.0, 0.0);                                                                          \
        uint n = PACKED ? word >> 16 : imageLoad(u_age[C], px).r;                                                       \
        if ((HOST_OUT_MASK & (1u << C)) != 0u && store) imageStore(u_host_out[C], px, v);                              \
        if ((HOST_AGE_MASK & (1u << C)) != 0u && store) imageStore(u_host_age_out[C], px, uvec4(n));                   \
    }
RRC_COPY_OUT_SLOT(0)
RRC_COPY_OUT_SLOT(1)
RRC_COPY_OUT_SLOT(2)
RRC_COPY_OUT_SLOT(3)
#undef RRC_COPY_OUT_SLOT

// COPY_OUT: one invocation a pixel, after RESOLVE_LISTED, bound as the next
// frame (its history inputs are this frame's results): the host's output and
// age images, and with COPY_MASK its mask, get the library's results.
void rrc_copy_out() {
    ivec2 size = imageSize(u_prev_depth);
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    rrc_store = all(lessThan(id, size));
    ivec2 px = min(id, size - 1);
    rrc_copy_out_0(px, rrc_store);
    rrc_copy_out_1(px, rrc_store);
    rrc_copy_out_2(px, rrc_store);
    rrc_copy_out_3(px, rrc_store);
    if (COPY_MASK && rrc_store) imageStore(u_mask, px, uvec4(texelFetch(s_classified, px, 0).r));
}

void main() { rrc_copy_out(); }
