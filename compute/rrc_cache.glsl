// The shading cache (docs/CONVENTIONS.md, "The shading cache"): which hits
// of REUSE channels are refreshed and the mask bits of a pixel (classify's
// quad list: rrc_list.glsl).  A function library of the per-pixel
// passes (rrc_module_frame.comp): it reads the ages from rrc_channel_slots.glsl's images.
#ifndef RRC_CACHE_GLSL
#define RRC_CACHE_GLSL

#include "rrc_depth.glsl"          // pc.refresh_phase
#include "rrc_channel_slots.glsl"  // CH*_BLEND, the history and age images
#include "rrc_io.glsl"              // RRC_LOAD

layout(constant_id = RRC_SPEC_REFRESH_POLICY) const uint REFRESH_POLICY = RRC_REFRESH_NONE;
layout(constant_id = RRC_SPEC_REFRESH_PERIOD) const uint REFRESH_PERIOD = 1u;
layout(constant_id = RRC_SPEC_REFRESH_TILES_X) const uint REFRESH_TILES_X = 1u;
layout(constant_id = RRC_SPEC_REFRESH_TILES_Y) const uint REFRESH_TILES_Y = 1u;
layout(constant_id = RRC_SPEC_MAX_LIFETIME) const uint MAX_LIFETIME = 0u;

// Slot c holds a REUSE channel.  Without one, refresh never happens and
// every line below folds away.
const bool REUSE0 = CH_COUNT > 0u && CH0_blend == RRC_BLEND_REUSE;
const bool REUSE1 = CH_COUNT > 1u && CH1_blend == RRC_BLEND_REUSE;
const bool REUSE2 = CH_COUNT > 2u && CH2_blend == RRC_BLEND_REUSE;
const bool REUSE3 = CH_COUNT > 3u && CH3_blend == RRC_BLEND_REUSE;
const bool HAS_REUSE = REUSE0 || REUSE1 || REUSE2 || REUSE3;

// The 32-bit integer hash of CONVENTIONS.md (RANDOM's per-block offset).
uint rrc_hash(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// The policy picks this pixel this frame; pc.refresh_phase = t mod n.
bool rrc_refresh_due(ivec2 px, ivec2 size) {
    const uint n = REFRESH_PERIOD;
    if (REFRESH_POLICY == RRC_REFRESH_TILED) {
        uint tx = uint(px.x) * REFRESH_TILES_X / uint(size.x);
        uint ty = uint(px.y) * REFRESH_TILES_Y / uint(size.y);
        return (pc.refresh_phase + tx + REFRESH_TILES_X * ty) % n == 0u;
    }
    if (REFRESH_POLICY == RRC_REFRESH_RANDOM) {
        uint q = uint(px.x >> 1) + ((uint(size.x) + 1u) >> 1) * uint(px.y >> 1);
        uint d = (q % n + rrc_hash(q / n) % n) % n;
        return (pc.refresh_phase + d) % n == 0u;
    }
    return false;
}

// Slot C's age at the reprojected nearest texel, or 0xFFFFFFFF for a slot
// that is not REUSE (it neither lowers nor raises the range below).  Packed
// channels keep the age in the history word.  One function a slot
// (storage-image arrays are indexed by constants), emitted by RRC_REUSE_AGE.
#define RRC_REUSE_AGE(C)                                                                              \
    uint rrc_reuse_age_##C(ivec2 t) {                                                                \
        if (!REUSE##C) return 0xFFFFFFFFu;                                                            \
        const bool PACKED = CH##C##_precision && !CH##C##_components; /* fp16, 1 component */ \
        return PACKED ? (RRC_LOAD(1u, 4u, imageLoad(u_hist_packed[C], t).r) >> 16)                   \
                      : RRC_LOAD(1u, 2u, imageLoad(u_age[C], t).r);                                   \
    }
RRC_REUSE_AGE(0)
RRC_REUSE_AGE(1)
RRC_REUSE_AGE(2)
RRC_REUSE_AGE(3)
#undef RRC_REUSE_AGE

// HIT, REFRESHED, BACKGROUND and INVALID_GEOMETRY of a pixel whose
// geometry (and hit test) is g.
uint rrc_cache_mask(ivec2 px, ivec2 size, RrcGeometry g) {
    uint mask = (g.background ? RRC_MASK_BACKGROUND : 0u) | (g.invalid ? RRC_MASK_INVALID_GEOMETRY : 0u);
    bool refresh = false;
    if (HAS_REUSE && g.hit) {
        // The REUSE slots' smallest and largest age.
        uint a0 = rrc_reuse_age_0(g.taps.nearest), a1 = rrc_reuse_age_1(g.taps.nearest);
        uint a2 = rrc_reuse_age_2(g.taps.nearest), a3 = rrc_reuse_age_3(g.taps.nearest);
        uint amin = min(min(a0, a1), min(a2, a3));
        uint amax = max(max(REUSE0 ? a0 : 0u, REUSE1 ? a1 : 0u), max(REUSE2 ? a2 : 0u, REUSE3 ? a3 : 0u));
        refresh = rrc_refresh_due(px, size) || amin == 0u || (MAX_LIFETIME > 0u && amax >= MAX_LIFETIME);
    }
    return mask | (g.hit ? (refresh ? RRC_MASK_REFRESHED : RRC_MASK_HIT) : 0u);
}

#endif
