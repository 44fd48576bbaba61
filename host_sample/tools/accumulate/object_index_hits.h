// Object-index false hits: a hit whose pixel's object id differs from the id
// at a previous-frame bilinear tap of non-zero weight at its reprojected
// position (the rule rrc_context_desc.use_object_id enforces, rrc.h), and
// the older, looser count by the nearest previous texel alone.  Shared by
// rrc-blender-check (blender/check_passes.cpp) and rrc_offline_test so both
// count the same way (docs/measurements/OFFLINE.md).  Header only, no library needed.
#ifndef RRC_ACCUMULATE_OBJECT_INDEX_HITS_H
#define RRC_ACCUMULATE_OBJECT_INDEX_HITS_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rrc_cli {

/** Below this bilinear weight a tap's weight may be zero in the kernel's
 *  fp32 arithmetic and not here, or the reverse (q carries ~1e-5 px of
 *  rounding at 64 px): such a tap decides nothing for certain. */
constexpr float kBorderlineTapWeight = 1e-4f;

/** What the previous frame holds under one reprojected pixel. */
struct TapObjects {
    bool nearest_foreign = false; /* the nearest texel has another id */
    bool foreign = false;         /* a tap of weight > kBorderlineTapWeight has another id */
    bool borderline = false;      /* only taps of weight in (0, kBorderlineTapWeight] have another id */
};

/** The taps of previous-frame sample coordinate (qx, qy) (texel centres at
 *  i + 0.5; docs/CONVENTIONS.md "Coordinates and jitter"), with the
 *  kernel's arithmetic: p = q - 0.5, i0 = floor(p), f = p - i0, taps
 *  clamped per axis, weights (1-fx)(1-fy), fx(1-fy), (1-fx)fy, fx fy. */
inline TapObjects tap_objects(int width, int height, float qx, float qy, uint32_t id, const std::vector<uint32_t>& prev_ids) {
    TapObjects t;
    auto at = [&](int x, int y) {
        return prev_ids[std::size_t(std::clamp(y, 0, height - 1)) * std::size_t(width) + std::clamp(x, 0, width - 1)];
    };
    t.nearest_foreign = at(int(std::floor(qx)), int(std::floor(qy))) != id;
    const float px = qx - 0.5f, py = qy - 0.5f;
    const float x0 = std::floor(px), y0 = std::floor(py);
    const float fx = px - x0, fy = py - y0;
    const float w[4] = {(1.0f - fx) * (1.0f - fy), fx * (1.0f - fy), (1.0f - fx) * fy, fx * fy};
    for (int k = 0; k < 4; ++k) {
        if (!(w[k] > 0.0f) || at(int(x0) + (k & 1), int(y0) + (k >> 1)) == id) continue;
        (w[k] > kBorderlineTapWeight ? t.foreign : t.borderline) = true;
    }
    if (t.foreign) t.borderline = false;
    return t;
}

/** The previous-frame sample coordinate of pixel (i, j) from Blender's
 *  Vector.X/Y (previous minus current, pixels, y up), computed as rrc does
 *  from what rrc-accumulate's preset hands it: uv_prev = uv + v * scale with
 *  the fp32 scale (1/W, -1/H), then q = uv_prev * size (no jitter). */
inline void blender_prev_position(int width, int height, int i, int j, float vx, float vy, float& qx, float& qy) {
    const float sx = float(1.0 / width), sy = float(-1.0 / height);
    const float ux = (float(i) + 0.5f) / float(width) + vx * sx, uy = (float(j) + 0.5f) / float(height) + vy * sy;
    qx = ux * float(width);
    qy = uy * float(height);
}

/** Counts over one frame's non-background pixels (rrc.mask bits: 1 HIT,
 *  4 BACKGROUND). */
struct ObjectIndexHits {
    int64_t tested = 0;          /* non-background pixels */
    int64_t hits = 0;            /* HIT pixels */
    int64_t nearest_foreign = 0; /* hits whose nearest previous texel has another id */
    int64_t foreign = 0;         /* object-index false hits: a tap of non-zero weight on another id */
    int64_t borderline = 0;      /* hits whose only foreign taps are below kBorderlineTapWeight */
    ObjectIndexHits& operator+=(const ObjectIndexHits& o) {
        tested += o.tested;
        hits += o.hits;
        nearest_foreign += o.nearest_foreign;
        foreign += o.foreign;
        borderline += o.borderline;
        return *this;
    }
};

/** One frame of a Blender render: `mask` the tool's rrc.mask, ids of this
 *  and the previous frame, Vector.X/Y of this frame.  `per_pixel`, if
 *  given, receives each pixel's TapObjects (hits only; others stay false). */
inline ObjectIndexHits count_object_index_hits(int width, int height, const std::vector<float>& mask, const std::vector<uint32_t>& ids,
                                               const std::vector<uint32_t>& prev_ids, const std::vector<float>& vector_x,
                                               const std::vector<float>& vector_y, std::vector<TapObjects>* per_pixel = nullptr) {
    ObjectIndexHits c;
    if (per_pixel) per_pixel->assign(mask.size(), TapObjects{});
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            const std::size_t k = std::size_t(j) * std::size_t(width) + std::size_t(i);
            const int m = int(mask[k]);
            if (m & 4) continue;  // background
            ++c.tested;
            if (!(m & 1)) continue;
            ++c.hits;
            float qx = 0, qy = 0;
            blender_prev_position(width, height, i, j, vector_x[k], vector_y[k], qx, qy);
            const TapObjects t = tap_objects(width, height, qx, qy, ids[k], prev_ids);
            c.nearest_foreign += t.nearest_foreign;
            c.foreign += t.foreign;
            c.borderline += t.borderline;
            if (per_pixel) (*per_pixel)[k] = t;
        }
    return c;
}

}  // namespace rrc_cli

#endif
