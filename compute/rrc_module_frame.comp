// The per-pixel passes: FUSED (the frame in one dispatch), CLASSIFY, RESOLVE
// and RESOLVE_LISTED (the shading cache's passes; docs/design/frame-plan.md), one body selected by the PASS specialization constant:
// reverse reprojection, the epsilon-depth hit test and the lambda recursive
// filter for up to RRC_MAX_CHANNELS channels.
// Written for lavapipe's costs (every instruction and image operation is paid, a store most;
// shared memory is emulated lane by lane): plain storage-image loads with
// format qualifiers, one set of bilinear weights shared by the depth test and
// every history fetch, value and age in one word for 1-component fp16 channels, wide 128x1 workgroups, no shared memory, straight-line
// code where the specialization constants have folded the branches.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "rrc_values.glsl"  // RRC_MAX_CHANNELS, RRC_MASK_*, spec ids, bindings

layout(local_size_x_id = RRC_SPEC_GROUP_SIZE_X, local_size_y_id = RRC_SPEC_GROUP_SIZE_Y) in;

// This pass's bindings, exactly (rrc_module_bindings.h; the library's layout is made from the same list).
#include "rrc_bindings.glsl"
RRC_MODULE_FRAME_BINDINGS(RRC_DECLARE)

#include "rrc_reproject.glsl"
#include "rrc_filter.glsl"
#include "rrc_channel_slots.glsl"
#include "rrc_mask.glsl"
#include "rrc_cache.glsl"
#include "rrc_list.glsl"
RRC_FILL_LIST_APPENDER  // rrc_list_fill
#include "rrc_view_lobe.glsl"
#include "rrc_io_flush.glsl"  // the counted image operations into the statistics buffer

// The frame's statistics: an optional interop output, its own pipeline
// variant (plugin/accumulate_pipeline.h, KernelVariant): off, its code is compiled out.
#ifdef RRC_WITHOUT_STATS
const bool STATS = false;  // the feature's code removed (tests/spirv)
#else
layout(constant_id = RRC_SPEC_STATS) const bool STATS = false;
#endif

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

// Every channel is REUSE: a shading cache.  Classify then writes the HITs'
// channels (a HIT reuses the cached value, which needs no sample) and
// resolve runs only on the listed quads (docs/design/frame-plan.md).
// (One && or || a constant: glslang folds those into specialization-constant
// operations, but turns a nested mix of them into run-time code.)
const bool ACCUMULATES0 = CH_COUNT > 0u && CH0_blend != RRC_BLEND_REUSE;
const bool ACCUMULATES1 = CH_COUNT > 1u && CH1_blend != RRC_BLEND_REUSE;
const bool ACCUMULATES2 = CH_COUNT > 2u && CH2_blend != RRC_BLEND_REUSE;
const bool ACCUMULATES3 = CH_COUNT > 3u && CH3_blend != RRC_BLEND_REUSE;
const bool ALL_REUSE = !(ACCUMULATES0 || ACCUMULATES1 || ACCUMULATES2 || ACCUMULATES3);
// Some channel has a spatial fill: the passes that write channels list its pixels.
const bool FILL0 = CH_COUNT > 0u && CH0_fill_age;
const bool FILL1 = CH_COUNT > 1u && CH1_fill_age;
const bool FILL2 = CH_COUNT > 2u && CH2_fill_age;
const bool FILL3 = CH_COUNT > 3u && CH3_fill_age;
const bool FILL_ANY = FILL0 || FILL1 || FILL2 || FILL3;
// Some channel has a view lobe: the pixel's view turn is formed once for all (rrc_view_lobe.glsl).
const bool VIEW0 = CH_COUNT > 0u && CH0_view_lobe;
const bool VIEW1 = CH_COUNT > 1u && CH1_view_lobe;
const bool VIEW2 = CH_COUNT > 2u && CH2_view_lobe;
const bool VIEW3 = CH_COUNT > 3u && CH3_view_lobe;
const bool VIEW_ANY = VIEW0 || VIEW1 || VIEW2 || VIEW3;

// The module's RRC_SLOTS slots' updates, rrc_channel_0 .. rrc_channel_<RRC_SLOTS - 1>
// (rrc_channel_slots.glsl); slots past them are not compiled.
#define RRC_CH 0
#include "rrc_channel.glsl"
#undef RRC_CH
#if RRC_SLOTS > 1
#define RRC_CH 1
#include "rrc_channel.glsl"
#undef RRC_CH
#endif
#if RRC_SLOTS > 2
#define RRC_CH 2
#include "rrc_channel.glsl"
#undef RRC_CH
#endif
#if RRC_SLOTS > 3
#define RRC_CH 3
#include "rrc_channel.glsl"
#undef RRC_CH
#endif

// One pixel, every channel: FUSED, RESOLVE, CLASSIFY (the mask; with
// ALL_REUSE the HITs' channels too) and RESOLVE_LISTED (the listed pixels
// that are not HITs; they need no reprojection: a REUSE channel takes the
// sample there).  `store`: the pixel is inside the frame (and, listed, in the list).
void rrc_pixel_at(ivec2 px, bool store) {
    ivec2 size = rrc_size();
    rrc_store = store;
    const bool LISTED = PASS == RRC_PASS_RESOLVE_LISTED;
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
        mask = PASS == RRC_PASS_RESOLVE ? rrc_classified(px) & kGeometryBits : rrc_cache_mask(px, size, g);
    }
    // Classify writes the mask only, unless every channel is REUSE.
    const bool CHANNELS = PASS != RRC_PASS_CLASSIFY || ALL_REUSE;
    // Accumulating channels take the hit test's answer (a refresh is a hit to
    // them); REUSE channels reuse only on HIT.
    bool hit_any = (mask & (RRC_MASK_HIT | RRC_MASK_REFRESHED)) != 0u;
    bool hit_cached = (mask & RRC_MASK_HIT) != 0u;
    // Which pass writes this pixel's channels: classify the HITs, resolve_listed the rest.
    bool channel_store = PASS == RRC_PASS_CLASSIFY ? store && hit_cached : LISTED ? store && !hit_cached : store;
    bool young = false;  // some channel with a fill has n < fill_age here (the slots' updates say)
    // The view turn theta, once for every slot with a view lobe (rrc_view_lobe.glsl), where the
    // channels blend: not in classify, which writes only REUSE channels (they have no lobe).
    // The lighting's turn phi adds to it (docs/CONVENTIONS.md, "The view-dependent history").
    float view_theta = 0.0;
    if (VIEW_ANY && PASS != RRC_PASS_CLASSIFY) {
        if (hit_any) view_theta = rrc_view_turn(px, size) + u_view.d.w;
    }

    // Each slot's update: its channel, the mask's INVALID_SAMPLE, and whether it is young.
    if (CHANNELS) {
        rrc_channel_0(px, g, hit_any, hit_cached, channel_store, view_theta, mask, young);
#if RRC_SLOTS > 1
        rrc_channel_1(px, g, hit_any, hit_cached, channel_store, view_theta, mask, young);
#endif
#if RRC_SLOTS > 2
        rrc_channel_2(px, g, hit_any, hit_cached, channel_store, view_theta, mask, young);
#endif
#if RRC_SLOTS > 3
        rrc_channel_3(px, g, hit_any, hit_cached, channel_store, view_theta, mask, young);
#endif
    }

    if (store) {
        rrc_io_store(1u);
        imageStore(u_mask, px, uvec4(mask));
    }
    if (FILL_ANY && CHANNELS && channel_store && young && !g.background) rrc_list_fill(px, size);
    rrc_count(mask, PASS != RRC_PASS_RESOLVE && !LISTED, PASS != RRC_PASS_CLASSIFY);
    rrc_io_flush(store);
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

void main() {
    if (PASS == RRC_PASS_RESOLVE_LISTED)
        rrc_resolve_listed();
    else
        rrc_pixel();
}
