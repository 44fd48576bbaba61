#version 450
// The roof of a configuration: a copy kernel that reads, once each, every
// byte the API makes rrc's kernel read and writes every output once
// (docs/measurements/PERFORMANCE.md, "The roof", lists them).  No kernel that honours the
// API can move fewer bytes, so kernel time / roof time is how far the kernel
// is from the memory bound; repacking inside the library moves only the
// kernel, never this.
//
// Specialisation constants select the reads and writes of a configuration;
// everything a configuration does not use folds away.  Reads are plain
// imageLoad with a format qualifier (the cheapest read there is); writes
// have one where the API fixes the format.  128x1 workgroups: lavapipe runs
// a row segment per thread best.
//
// Outputs are exact copies of designated inputs, so a test can read them
// back and compare: values <- history, age out <- age in, depth copy <-
// depth, weight out <- previous weight, ids copy <- object id, mask <-
// nocache (or 0).  The remaining reads (samples, reprojection data,
// confidence, previous depth, previous ids) are folded into `sink`, which
// only sets bit 7 of the mask if it equals a run-time sentinel: the loads
// must happen, yet (barring a 2^-32 coincidence) no output changes.

layout(local_size_x = 128, local_size_y = 1) in;

// Reprojection input: 0 none (CAMERA), 1 rgba32f (PREV_CLIP, MOTION_DEPTH), 2 rg32f (MOTION).
layout(constant_id = 0) const uint REPROJECTION = 1u;
layout(constant_id = 1) const uint CHANNELS = 1u;
// Per channel slot, the history (and output) format: 0 r16f, 1 rgba16f, 2 r32f, 3 rgba32f.
// Samples are r32f or rgba32f (bit 0 of the kind): what renderers write and
// what keeps the layout within 64 storage images a stage.
layout(constant_id = 2) const uint KIND0 = 0u;
layout(constant_id = 3) const uint KIND1 = 0u;
layout(constant_id = 4) const uint KIND2 = 0u;
layout(constant_id = 5) const uint KIND3 = 0u;
// Bit c: channel c has confidence (samples' weight in, previous weight in, weight out).
layout(constant_id = 6) const uint CONFIDENCE_MASK = 0u;
layout(constant_id = 7) const bool NOCACHE = false;
layout(constant_id = 8) const bool OBJECT_ID = false;

layout(push_constant) uniform Push {
    uint width;
    uint height;
    uint sentinel;
} pc;

// Frame inputs, as the host passes them.
layout(binding = 0, r32f) uniform readonly image2D u_depth;
layout(binding = 1, rgba32f) uniform readonly image2D u_reproj4;
layout(binding = 2, rg32f) uniform readonly image2D u_reproj2;
layout(binding = 3, r8ui) uniform readonly uimage2D u_nocache;
layout(binding = 4, r32ui) uniform readonly uimage2D u_object_id;
// State carried from the previous frame.
layout(binding = 5, r32f) uniform readonly image2D u_prev_depth;
layout(binding = 6, r32ui) uniform readonly uimage2D u_prev_object_id;
// Per channel slot, one array per format.
layout(binding = 7, r32f) uniform readonly image2D u_samples_r32f[4];
layout(binding = 8, rgba32f) uniform readonly image2D u_samples_rgba32f[4];
layout(binding = 9, r16f) uniform readonly image2D u_hist_r16f[4];
layout(binding = 10, rgba16f) uniform readonly image2D u_hist_rgba16f[4];
layout(binding = 11, r32f) uniform readonly image2D u_hist_r32f[4];
layout(binding = 12, rgba32f) uniform readonly image2D u_hist_rgba32f[4];
layout(binding = 13, r16ui) uniform readonly uimage2D u_age[4];
layout(binding = 14, r32f) uniform readonly image2D u_confidence[4];
layout(binding = 15, r32f) uniform readonly image2D u_weight[4];
// Outputs.  The values go to the host's image, "any float format" in the
// API, so the write has no format (as the kernel's); the others have one
// fixed format and are written with it (also as the kernel's).
layout(binding = 16) uniform writeonly image2D u_values_out[4];
layout(binding = 17, r16ui) uniform writeonly uimage2D u_age_out[4];
layout(binding = 18, r32f) uniform writeonly image2D u_weight_out[4];
layout(binding = 19, r8ui) uniform writeonly uimage2D u_mask;
layout(binding = 20, r32f) uniform writeonly image2D u_depth_copy;
layout(binding = 21, r32ui) uniform writeonly uimage2D u_object_id_copy;

#define STORE(image, at, value) \
    if (in_image) imageStore(image, at, value)

uint fold(vec4 v, bool four) {
    uint s = floatBitsToUint(v.x);
    if (four) s ^= floatBitsToUint(v.y) ^ floatBitsToUint(v.z) ^ floatBitsToUint(v.w);
    return s;
}

// One channel slot, with a literal index: array indices stay constant
// expressions (no dynamic-indexing feature needed) and unused slots fold away.
#define RRC_ROOF_CHANNEL(C, KIND)                                                                    \
    if (C < CHANNELS) {                                                                              \
        const bool four = (KIND & 1u) != 0u;                                                         \
        const vec4 s = four ? imageLoad(u_samples_rgba32f[C], p) : imageLoad(u_samples_r32f[C], p);  \
        vec4 h;                                                                                      \
        if (KIND == 0u) h = imageLoad(u_hist_r16f[C], p);                                            \
        if (KIND == 1u) h = imageLoad(u_hist_rgba16f[C], p);                                         \
        if (KIND == 2u) h = imageLoad(u_hist_r32f[C], p);                                            \
        if (KIND == 3u) h = imageLoad(u_hist_rgba32f[C], p);                                         \
        sink ^= fold(s, four);                                                                       \
        STORE(u_values_out[C], p, h);                                                           \
        STORE(u_age_out[C], p, imageLoad(u_age[C], p));                                         \
        if ((CONFIDENCE_MASK & (1u << C)) != 0u) {                                                   \
            sink ^= floatBitsToUint(imageLoad(u_confidence[C], p).x);                                \
            STORE(u_weight_out[C], p, imageLoad(u_weight[C], p));                               \
        }                                                                                            \
    }

void main() {
    // No early return, as in rrc's kernel (compute/rrc_reproject.glsl,
    // rrc_store): lavapipe runs what follows a divergent return lane by lane.
    // Invocations beyond the image (the dispatch rounds up) load a clamped
    // texel and store nothing.
    const ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    const ivec2 size = ivec2(pc.width, pc.height);
    const bool in_image = all(lessThan(id, size));
    const ivec2 p = min(id, size - 1);
    uint sink = 0u;

    STORE(u_depth_copy, p, imageLoad(u_depth, p));
    if (REPROJECTION == 1u) sink ^= fold(imageLoad(u_reproj4, p), true);
    if (REPROJECTION == 2u) {
        const vec4 m = imageLoad(u_reproj2, p);
        sink ^= floatBitsToUint(m.x) ^ floatBitsToUint(m.y);
    }
    sink ^= floatBitsToUint(imageLoad(u_prev_depth, p).x);

    RRC_ROOF_CHANNEL(0, KIND0)
    RRC_ROOF_CHANNEL(1, KIND1)
    RRC_ROOF_CHANNEL(2, KIND2)
    RRC_ROOF_CHANNEL(3, KIND3)

    if (OBJECT_ID) {
        STORE(u_object_id_copy, p, imageLoad(u_object_id, p));
        sink ^= imageLoad(u_prev_object_id, p).x;
    }
    uint mask = NOCACHE ? imageLoad(u_nocache, p).x : 0u;
    if (sink == pc.sentinel) mask |= 0x80u;
    STORE(u_mask, p, uvec4(mask));
}
