#version 450
// The fused kernel: reverse reprojection, the epsilon-depth hit test and the
// lambda recursive filter for up to RRC_MAX_CHANNELS channels, one pass.
// Written for lavapipe's costs (every instruction and image operation is paid, a store most;
// shared memory is emulated lane by lane): plain storage-image loads with
// format qualifiers, one set of bilinear weights shared by the depth test and
// every history fetch, value and age in one word for 1-component fp16 channels, wide 128x1 workgroups, no shared memory, straight-line
// code where the specialization constants have folded the branches.
#extension GL_GOOGLE_include_directive : require

#include "rrc_values.glsl"  // RRC_MAX_CHANNELS, RRC_MASK_*, spec ids, bindings

layout(local_size_x_id = RRC_SPEC_GROUP_SIZE_X, local_size_y_id = RRC_SPEC_GROUP_SIZE_Y) in;

#include "rrc_reproject.glsl"
#include "rrc_filter.glsl"

layout(constant_id = RRC_SPEC_CHANNEL_COUNT) const uint CH_COUNT = 1u;

// Per-slot specialization constants: RRC_SPEC_CHANNEL(property, slot), i.e.
// id 16 + 4*property + slot (rrc_kernel_interface.h).
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_COMPONENTS, 0)) const uint CH0_COMPONENTS = 1u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_COMPONENTS, 1)) const uint CH1_COMPONENTS = 1u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_COMPONENTS, 2)) const uint CH2_COMPONENTS = 1u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_COMPONENTS, 3)) const uint CH3_COMPONENTS = 1u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FP16, 0)) const bool CH0_FP16 = true;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FP16, 1)) const bool CH1_FP16 = true;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FP16, 2)) const bool CH2_FP16 = true;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FP16, 3)) const bool CH3_FP16 = true;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_BLEND, 0)) const uint CH0_BLEND = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_BLEND, 1)) const uint CH1_BLEND = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_BLEND, 2)) const uint CH2_BLEND = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_BLEND, 3)) const uint CH3_BLEND = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FILTER, 0)) const uint CH0_FILTER = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FILTER, 1)) const uint CH1_FILTER = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FILTER, 2)) const uint CH2_FILTER = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FILTER, 3)) const uint CH3_FILTER = 0u;
#ifdef RRC_WITHOUT_CONFIDENCE  // the feature's code removed (tests/spirv)
const bool CH0_CONFIDENCE = false;
const bool CH1_CONFIDENCE = false;
const bool CH2_CONFIDENCE = false;
const bool CH3_CONFIDENCE = false;
#else
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_CONFIDENCE, 0)) const bool CH0_CONFIDENCE = false;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_CONFIDENCE, 1)) const bool CH1_CONFIDENCE = false;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_CONFIDENCE, 2)) const bool CH2_CONFIDENCE = false;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_CONFIDENCE, 3)) const bool CH3_CONFIDENCE = false;
#endif
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_LAMBDA, 0)) const float CH0_LAMBDA = 0.6;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_LAMBDA, 1)) const float CH1_LAMBDA = 0.6;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_LAMBDA, 2)) const float CH2_LAMBDA = 0.6;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_LAMBDA, 3)) const float CH3_LAMBDA = 0.6;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_AGE_CAP, 0)) const uint CH0_AGE_CAP = 255u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_AGE_CAP, 1)) const uint CH1_AGE_CAP = 255u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_AGE_CAP, 2)) const uint CH2_AGE_CAP = 255u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_AGE_CAP, 3)) const uint CH3_AGE_CAP = 255u;
// 0.4, the finishing steps (docs/CONVENTIONS.md, "Finishing steps"):
// RRC_SPEC_CHANNEL2(property, slot).  Each is off (false / 0) by default.
#define RRC_SLOTS2(T, NAME, property, off)                                                  \
    layout(constant_id = RRC_SPEC_CHANNEL2(RRC_CHANNEL2_PROPERTY_##property, 0)) const T CH0_##NAME = off; \
    layout(constant_id = RRC_SPEC_CHANNEL2(RRC_CHANNEL2_PROPERTY_##property, 1)) const T CH1_##NAME = off; \
    layout(constant_id = RRC_SPEC_CHANNEL2(RRC_CHANNEL2_PROPERTY_##property, 2)) const T CH2_##NAME = off; \
    layout(constant_id = RRC_SPEC_CHANNEL2(RRC_CHANNEL2_PROPERTY_##property, 3)) const T CH3_##NAME = off;
#define RRC_SLOTS_OFF(T, NAME, off) const T CH0_##NAME = off, CH1_##NAME = off, CH2_##NAME = off, CH3_##NAME = off;
#ifdef RRC_WITHOUT_RECTIFY  // the feature's code removed (tests/spirv)
RRC_SLOTS_OFF(bool, RECTIFY, false)
#else
RRC_SLOTS2(bool, RECTIFY, RECTIFY, false)
#endif
RRC_SLOTS2(float, RECTIFY_GAMMA, RECTIFY_GAMMA, 1.0)
RRC_SLOTS2(float, BLUR_G, BLUR_G, 0.125)
#ifdef RRC_WITHOUT_FILL  // the feature's code removed (tests/spirv)
RRC_SLOTS_OFF(uint, FILL_AGE, 0u)
#else
RRC_SLOTS2(uint, FILL_AGE, FILL_AGE, 0u)
#endif
RRC_SLOTS2(uint, FILL_RADIUS, FILL_RADIUS, 2u)
RRC_SLOTS2(float, FILL_TOLERANCE, FILL_TOLERANCE, 0.005)
RRC_SLOTS2(float, FILL_PRIOR, FILL_PRIOR, 0.0)
#undef RRC_SLOTS2
#undef RRC_SLOTS_OFF
// Slot selectors: called with a literal slot, they fold to one constant.
#define RRC_SLOT_SELECT(T, name) \
    T ch_##name(int c) { return c == 0 ? CH0_##name : c == 1 ? CH1_##name : c == 2 ? CH2_##name : CH3_##name; }
RRC_SLOT_SELECT(uint, COMPONENTS)
RRC_SLOT_SELECT(bool, FP16)
RRC_SLOT_SELECT(uint, BLEND)
RRC_SLOT_SELECT(uint, FILTER)
RRC_SLOT_SELECT(bool, CONFIDENCE)
RRC_SLOT_SELECT(float, LAMBDA)
RRC_SLOT_SELECT(uint, AGE_CAP)
RRC_SLOT_SELECT(bool, RECTIFY)
RRC_SLOT_SELECT(float, RECTIFY_GAMMA)
RRC_SLOT_SELECT(float, BLUR_G)
RRC_SLOT_SELECT(uint, FILL_AGE)
RRC_SLOT_SELECT(uint, FILL_RADIUS)
RRC_SLOT_SELECT(float, FILL_TOLERANCE)
RRC_SLOT_SELECT(float, FILL_PRIOR)

// Read too: resolve and the list read classify's mask where classify wrote it (MASK_IN_PLACE).
layout(set = 0, binding = RRC_BINDING_MASK, r8ui) uniform uimage2D u_mask;

// Per-channel images, arrays indexed by slot.  Slots and format variants a
// configuration does not use are bound to 1x1 placeholders and never touched.
layout(set = 0, binding = RRC_BINDING_SAMPLE1, r32f) uniform readonly image2D u_sample1[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_SAMPLE4, rgba32f) uniform readonly image2D u_sample4[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_CONFIDENCE, r32f) uniform readonly image2D u_confidence[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_HIST_PACKED, r32ui) uniform readonly uimage2D u_hist_packed[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_HIST_RGBA16F, rgba16f) uniform readonly image2D u_hist_rgba16f[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_HIST_R32F, r32f) uniform readonly image2D u_hist_r32f[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_HIST_RGBA32F, rgba32f) uniform readonly image2D u_hist_rgba32f[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_AGE, r16ui) uniform readonly uimage2D u_age[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_WEIGHT, r32f) uniform readonly image2D u_weight[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_HIST_OUT) uniform writeonly image2D u_hist_out[RRC_MAX_CHANNELS];  // any float format
// R16_UINT ages, or for packed channels their R32_UINT value|age words (so declared without a format).
layout(set = 0, binding = RRC_BINDING_AGE_OUT) uniform writeonly uimage2D u_age_out[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_WEIGHT_OUT, r32f) uniform writeonly image2D u_weight_out[RRC_MAX_CHANNELS];
layout(set = 0, binding = RRC_BINDING_HOST_SAMPLES) uniform sampler2D s_samples[RRC_MAX_CHANNELS];     // INTEROP
layout(set = 0, binding = RRC_BINDING_HOST_CONFIDENCE) uniform sampler2D s_confidence[RRC_MAX_CHANNELS];  // INTEROP
layout(set = 0, binding = RRC_BINDING_HOST_OUT) uniform writeonly image2D u_host_out[RRC_MAX_CHANNELS];  // INTEROP: any float format
layout(set = 0, binding = RRC_BINDING_HOST_AGE_OUT, r16ui) uniform writeonly uimage2D u_host_age_out[RRC_MAX_CHANNELS];  // INTEROP, optional
layout(set = 0, binding = RRC_BINDING_FALLBACK) uniform sampler2D s_fallback[RRC_MAX_CHANNELS];  // FILL: the host's fallback estimate

// Optional interop outputs, each its own pipeline variant (plugin/accumulate_pipeline.h,
// KernelVariant): off, their code is compiled out.
#ifdef RRC_WITHOUT_STATS
const bool STATS = false;  // the feature's code removed (tests/spirv)
#else
layout(constant_id = RRC_SPEC_STATS) const bool STATS = false;
#endif
#ifdef RRC_WITHOUT_HOST_AGE
const uint HOST_AGE_MASK = 0u;  // the feature's code removed (tests/spirv)
#else
layout(constant_id = RRC_SPEC_HOST_AGE_MASK) const uint HOST_AGE_MASK = 0u;
#endif
// rrc_vulkan_frame_stats (include/rrc/rrc_vulkan.h), cleared by the library before the dispatch.
layout(std430, set = 0, binding = RRC_BINDING_STATS) buffer Stats { uint counters[RRC_STAT_COUNT]; } u_stats;

#include "rrc_cache.glsl"

// The spatial fill's depth test |delta_q - delta_p| <= tau delta_p on the
// proxy delta (docs/CONVENTIONS.md, "The spatial fill": d, 1/(1 - z), 1/z),
// multiplied out so that no tap divides: STANDARD |z_q - z_p| <= tau (1 - z_q),
// REVERSED |z_p - z_q| <= tau z_q (both denominators positive off background).
bool rrc_fill_similar(float d_q, float d_p, float tau) {
    if (DEPTH_MODE == RRC_DEPTH_MODE_STANDARD) return abs(d_q - d_p) <= tau * (1.0 - d_q);
    if (DEPTH_MODE == RRC_DEPTH_MODE_REVERSED) return abs(d_p - d_q) <= tau * d_q;
    return abs(d_q - d_p) <= tau * d_p;
}

// The frame's statistics (interop, STATS): `geometry` counts what the hit
// test decides, `samples` the invalid samples (classify and resolve split them).
void rrc_count(uint mask, bool geometry, bool samples) {
    if (!STATS || !rrc_store) return;
    bool hit = (mask & RRC_MASK_HIT) != 0u, refreshed = (mask & RRC_MASK_REFRESHED) != 0u;
    bool background = (mask & RRC_MASK_BACKGROUND) != 0u;
    if (geometry) {
        if (hit) atomicAdd(u_stats.counters[RRC_STAT_HITS], 1u);
        if (!hit && !refreshed && !background) atomicAdd(u_stats.counters[RRC_STAT_MISSES], 1u);
        if (background) atomicAdd(u_stats.counters[RRC_STAT_BACKGROUND], 1u);
        if ((mask & RRC_MASK_INVALID_GEOMETRY) != 0u) atomicAdd(u_stats.counters[RRC_STAT_INVALID_GEOMETRY], 1u);
        if (refreshed) atomicAdd(u_stats.counters[RRC_STAT_REFRESHED], 1u);
    }
    if (samples && (mask & RRC_MASK_INVALID_SAMPLE) != 0u) atomicAdd(u_stats.counters[RRC_STAT_INVALID_SAMPLES], 1u);
}

// Which channel slots write the host's output image in this pass (interop,
// and the standalone fill's displayed values): chosen by the frame plan.
layout(constant_id = RRC_SPEC_HOST_OUT_MASK) const uint HOST_OUT_MASK = 0u;
// COPY_OUT: also copy classify's mask into u_mask (the host's).
layout(constant_id = RRC_SPEC_COPY_MASK) const bool COPY_MASK = false;
// Classify's mask is in u_mask (the image classify wrote: storage loads,
// cheaper than the sampler of s_classified on lavapipe), else in s_classified.
layout(constant_id = RRC_SPEC_MASK_IN_PLACE) const bool MASK_IN_PLACE = false;
uint rrc_classified(ivec2 px) { return MASK_IN_PLACE ? imageLoad(u_mask, px).r : texelFetch(s_classified, px, 0).r; }

// Every channel is REUSE: a shading cache.  Classify then writes the HITs'
// channels (a HIT reuses the cached value, which needs no sample) and
// resolve runs only on the listed quads (docs/PERFORMANCE.md, "The frame plan").
// (One && or || a constant: glslang folds those into specialization-constant
// operations, but turns a nested mix of them into run-time code.)
const bool ACCUMULATES0 = CH_COUNT > 0u && CH0_BLEND != RRC_BLEND_REUSE;
const bool ACCUMULATES1 = CH_COUNT > 1u && CH1_BLEND != RRC_BLEND_REUSE;
const bool ACCUMULATES2 = CH_COUNT > 2u && CH2_BLEND != RRC_BLEND_REUSE;
const bool ACCUMULATES3 = CH_COUNT > 3u && CH3_BLEND != RRC_BLEND_REUSE;
const bool ALL_REUSE = !(ACCUMULATES0 || ACCUMULATES1 || ACCUMULATES2 || ACCUMULATES3);
// Some channel has a spatial fill: the passes that write channels list its pixels.
const bool FILL0 = CH_COUNT > 0u && CH0_FILL_AGE != 0u;
const bool FILL1 = CH_COUNT > 1u && CH1_FILL_AGE != 0u;
const bool FILL2 = CH_COUNT > 2u && CH2_FILL_AGE != 0u;
const bool FILL3 = CH_COUNT > 3u && CH3_FILL_AGE != 0u;
const bool FILL_ANY = FILL0 || FILL1 || FILL2 || FILL3;

// The fill list (rrc_kernel_interface.h): the pixels the spatial fill runs on.
layout(std430, set = 0, binding = RRC_BINDING_FILL_LIST) buffer FillList { uint words[]; } u_fill;

// Appends px to the fill list; the indirect dispatch's x is the largest
// group an entry falls in, + 1: raised only by the first entry of each group.
void rrc_list_fill(ivec2 px) {
    uint slot = atomicAdd(u_fill.words[RRC_FILL_LIST_COUNT], 1u);
    u_fill.words[RRC_FILL_LIST_FIRST + slot] = uint(px.x) | (uint(px.y) << 16);
    if (slot % RRC_FILL_LIST_PER_GROUP == 0u) atomicMax(u_fill.words[RRC_FILL_LIST_DISPATCH], slot / RRC_FILL_LIST_PER_GROUP + 1u);
}

// One pixel, every channel: FUSED, RESOLVE, CLASSIFY (the mask; with
// ALL_REUSE the HITs' channels too) and RESOLVE_LISTED (the listed pixels
// that are not HITs; they need no reprojection: a REUSE channel takes the
// sample there).  `store`: the pixel is inside the frame (and, listed, in the list).
void rrc_pixel_at(ivec2 px, bool store) {
    ivec2 size = rrc_size();
    rrc_store = store;
    const bool LISTED = PHASE == RRC_PHASE_RESOLVE_LISTED;
    RrcGeometry g;
    uint mask;
    const uint kGeometryBits = RRC_MASK_HIT | RRC_MASK_REFRESHED | RRC_MASK_BACKGROUND | RRC_MASK_INVALID_GEOMETRY;
    if (LISTED) {
        mask = rrc_classified(px) & kGeometryBits;
        g.background = (mask & RRC_MASK_BACKGROUND) != 0u;
        g.invalid = false, g.hit = false;
        g.taps = rrc_taps(vec2(px) + 0.5, size);  // unused: folded away
    } else {
        g = rrc_reproject(px, size);
        mask = PHASE == RRC_PHASE_RESOLVE ? rrc_classified(px) & kGeometryBits : rrc_cache_mask(px, size, g);
    }
    // Classify writes the mask only, unless every channel is REUSE.
    const bool CHANNELS = PHASE != RRC_PHASE_CLASSIFY || ALL_REUSE;
    // Accumulating channels take the hit test's answer (a refresh is a hit to
    // them); REUSE channels reuse only on HIT.
    bool hit_any = (mask & (RRC_MASK_HIT | RRC_MASK_REFRESHED)) != 0u;
    bool hit_cached = (mask & RRC_MASK_HIT) != 0u;
    // Which pass writes this pixel's channels: classify the HITs, resolve_listed the rest.
    bool channel_store = PHASE == RRC_PHASE_CLASSIFY ? store && hit_cached : LISTED ? store && !hit_cached : store;
    bool young = false;  // some channel with a fill has n < fill_age here (set by rrc_channel.glsl)

#define RRC_CH 0
#include "rrc_channel.glsl"
#undef RRC_CH
#define RRC_CH 1
#include "rrc_channel.glsl"
#undef RRC_CH
#define RRC_CH 2
#include "rrc_channel.glsl"
#undef RRC_CH
#define RRC_CH 3
#include "rrc_channel.glsl"
#undef RRC_CH

    if (store) imageStore(u_mask, px, uvec4(mask));
    if (FILL_ANY && CHANNELS && channel_store && young && !g.background) rrc_list_fill(px);
    rrc_count(mask, PHASE != RRC_PHASE_RESOLVE && !LISTED, PHASE != RRC_PHASE_CLASSIFY);
}

// FUSED, CLASSIFY and RESOLVE: one invocation a pixel.
void rrc_pixel() {
    ivec2 size = rrc_size();
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    // The dispatch rounds up: no early return (rrc_reproject.glsl says why).
    rrc_pixel_at(min(id, size - 1), all(lessThan(id, size)));
}

// RESOLVE_LISTED: dispatched indirectly from classify's quad list, groups
// of RRC_QUADS_PER_GROUP quads; two invocations a quad, one a row of two
// pixels: the group's first half takes the quads' top rows, the second half
// their bottom rows, so neighbouring invocations touch neighbouring quads.
void rrc_resolve_listed() {
    ivec2 size = rrc_size();
    uint lane = gl_LocalInvocationID.x;
    uint count = u_quads.words[RRC_QUAD_LIST_COUNT];
    uint slot = gl_WorkGroupID.x * RRC_QUADS_PER_GROUP + lane % RRC_QUADS_PER_GROUP;
    bool listed = slot < count;
    uint word = u_quads.words[RRC_QUAD_LIST_FIRST_QUAD + min(slot, max(count, 1u) - 1u)];
    ivec2 row = 2 * ivec2(word & 0xFFFFu, word >> 16) + ivec2(0, int(lane / RRC_QUADS_PER_GROUP));
    for (int k = 0; k < 2; ++k) {
        ivec2 px = row + ivec2(k, 0);
        rrc_pixel_at(min(px, size - 1), listed && all(lessThan(px, size)));
    }
}

// LIST: one invocation a 2x2 quad, after CLASSIFY wrote the mask (a pass of
// its own: one invocation a quad would run the reprojection of four pixels
// in a row, about twice the time of one a pixel on lavapipe).  The quad is
// listed when one of its pixels inside the frame is not a HIT.
void rrc_list_quads() {
    ivec2 size = imageSize(u_mask);
    ivec2 quads = (size + 1) / 2;
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    ivec2 q = min(id, quads - 1);
    bool listed = false;
    for (int k = 0; k < 4; ++k) {
        ivec2 px = 2 * q + ivec2(k & 1, k >> 1);
        bool inside = all(lessThan(px, size));
        uint mask = rrc_classified(min(px, size - 1));
        listed = listed || (inside && (mask & RRC_MASK_HIT) == 0u);
    }
    if (listed && all(lessThan(id, quads))) rrc_list_quad(q);
}

// COPY_OUT: one invocation a pixel, after RESOLVE_LISTED, bound as the next
// frame (its history inputs are this frame's results): the host's output and
// age images, and with COPY_MASK its mask, get the library's results.
#define RRC_COPY_OUT_SLOT(C)                                                                                            \
    if (C < CH_COUNT) {                                                                                                 \
        const bool PACKED = CH##C##_FP16 && CH##C##_COMPONENTS == 1u;                                                    \
        uint word = PACKED ? imageLoad(u_hist_packed[C], px).r : 0u;                                                    \
        vec4 v = PACKED ? vec4(unpackHalf2x16(word).x, 0.0, 0.0, 0.0)                                                  \
                 : CH##C##_FP16 ? imageLoad(u_hist_rgba16f[C], px)                                                      \
                 : (CH##C##_COMPONENTS == 1u ? imageLoad(u_hist_r32f[C], px) : imageLoad(u_hist_rgba32f[C], px));        \
        if (CH##C##_COMPONENTS == 1u) v = vec4(v.x, 0.0, 0.0, 0.0);                                                     \
        uint n = PACKED ? word >> 16 : imageLoad(u_age[C], px).r;                                                       \
        if (rrc_store && (HOST_OUT_MASK & (1u << C)) != 0u) imageStore(u_host_out[C], px, v);                          \
        if (rrc_store && (HOST_AGE_MASK & (1u << C)) != 0u) imageStore(u_host_age_out[C], px, uvec4(n));               \
    }
void rrc_copy_out() {
    ivec2 size = imageSize(u_prev_depth);
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    rrc_store = all(lessThan(id, size));
    ivec2 px = min(id, size - 1);
    RRC_COPY_OUT_SLOT(0)
    RRC_COPY_OUT_SLOT(1)
    RRC_COPY_OUT_SLOT(2)
    RRC_COPY_OUT_SLOT(3)
    if (COPY_MASK && rrc_store) imageStore(u_mask, px, uvec4(texelFetch(s_classified, px, 0).r));
}
#undef RRC_COPY_OUT_SLOT

// FILL: one invocation a listed pixel (the fill list, indirect), after the
// frame's channels, bound as the next frame would be (its history inputs are
// this frame's results, its previous depth this frame's depth): the
// displayed value of every channel with a fill, into u_host_out
// (docs/CONVENTIONS.md, "The spatial fill").  Every other pixel's displayed
// value is its history value, which the frame's pass wrote there.
void rrc_fill() {
    ivec2 size = imageSize(u_prev_depth);
    uint slot = gl_GlobalInvocationID.x;
    uint count = u_fill.words[RRC_FILL_LIST_COUNT];
    rrc_store = slot < count;  // no early return (rrc_reproject.glsl says why)
    uint word = u_fill.words[RRC_FILL_LIST_FIRST + min(slot, max(count, 1u) - 1u)];
    ivec2 px = min(ivec2(word & 0xFFFFu, word >> 16), size - 1);
    float d_p = imageLoad(u_prev_depth, px).r;
    bool fill_here = !rrc_is_background(d_p);
    bool valid_p = !rrc_is_invalid_depth(d_p);  // an invalid depth takes no neighbour, only the fallback

#define RRC_CH 0
#include "rrc_fill_channel.glsl"
#undef RRC_CH
#define RRC_CH 1
#include "rrc_fill_channel.glsl"
#undef RRC_CH
#define RRC_CH 2
#include "rrc_fill_channel.glsl"
#undef RRC_CH
#define RRC_CH 3
#include "rrc_fill_channel.glsl"
#undef RRC_CH
}

void main() {
    if (PHASE == RRC_PHASE_FILL)
        rrc_fill();
    else if (PHASE == RRC_PHASE_LIST)
        rrc_list_quads();
    else if (PHASE == RRC_PHASE_RESOLVE_LISTED)
        rrc_resolve_listed();
    else if (PHASE == RRC_PHASE_COPY_OUT)
        rrc_copy_out();
    else
        rrc_pixel();
}
