#include "bias_regions.h"

#include "clean_regions.h"

#include <rrc/rrc.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rrc_sweep {
namespace {

constexpr uint8_t kMaskHit = RRC_MASK_HIT, kMaskBackground = RRC_MASK_BACKGROUND, kMaskRefreshed = RRC_MASK_REFRESHED;

/** Where an edge starts: the background, an rrc miss (a disocclusion) or a depth jump. The depth is
 *  reversed z, proportional to 1/z (rrc_host::inverse_depth_jump). */
std::vector<uint8_t> edge_seeds(const RegionFrame& g, float jump) {
    const uint32_t w = g.width, h = g.height;
    std::vector<uint8_t> s(g.depth.size(), 0);
    auto d = [&](int x, int y) { return g.depth[(size_t)y * w + x]; };
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t p = (size_t)y * w + x;
            const uint8_t m = g.mask.empty() ? kMaskHit : g.mask[p];
            const bool seed = d(x, y) <= 0.0f || (m & kMaskBackground) || !(m & (kMaskHit | kMaskRefreshed)) ||
                              rrc_host::inverse_depth_jump(g.depth.data(), w, h, x, y, jump);
            s[p] = seed ? 1 : 0;
        }
    return s;
}

/** The previous value of pixel p (PreviousTarget's two kinds) in `out`; false where there is none. */
bool previous_value(const PreviousTarget& prev, size_t p, const float* position, const std::vector<uint8_t>& material_now, uint32_t w,
                    uint32_t h, int components, double* out) {
    if (prev.at_same_point) {
        if (!prev.scored[p] || prev.material[p] != material_now[p]) return false;
        for (int k = 0; k < components; ++k) out[k] = prev.values[p * prev.stride + k];
        return true;
    }
    const float* x = &position[p * 4];
    const double* m = prev.view_proj;  // column-major: clip = M (x, 1)
    double clip[4];
    for (int r = 0; r < 4; ++r) clip[r] = m[0 * 4 + r] * x[0] + m[1 * 4 + r] * x[1] + m[2 * 4 + r] * x[2] + m[3 * 4 + r];
    if (!(clip[3] > 0.0)) return false;
    const double px = (clip[0] / clip[3] + 1.0) * 0.5 * w - 0.5, py = (clip[1] / clip[3] + 1.0) * 0.5 * h - 0.5;
    if (!std::isfinite(px) || !std::isfinite(py)) return false;
    const int x0 = (int)std::floor(px), y0 = (int)std::floor(py);
    const double fx = px - x0, fy = py - y0;
    // Bilinear over the scored texels of the 2x2 footprint, renormalised.
    double sum = 0.0;
    for (int k = 0; k < components; ++k) out[k] = 0.0;
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            const int xx = x0 + dx, yy = y0 + dy;
            const double wt = (dx ? fx : 1.0 - fx) * (dy ? fy : 1.0 - fy);
            if (xx < 0 || yy < 0 || xx >= (int)w || yy >= (int)h || wt <= 0.0) continue;
            const size_t q = (size_t)yy * w + xx;
            if (!prev.scored[q]) continue;
            for (int k = 0; k < components; ++k) out[k] += wt * prev.values[q * prev.stride + k];
            sum += wt;
        }
    if (sum < 1e-6) return false;
    for (int k = 0; k < components; ++k) out[k] /= sum;
    return true;
}

}  // namespace

const char* region_name(int r) {
    static const char* const names[kRegionCount] = {"object", "edge", "young", "changed", "static"};
    return r >= 0 && r < kRegionCount ? names[r] : "unscored";
}

void mark_changes(std::vector<uint8_t>& changed, const CheckpointTarget& now, const PreviousTarget& prev, const float* position,
                  const std::vector<uint8_t>& material_now, uint32_t w, uint32_t h, float tau) {
    const size_t n = (size_t)w * h;
    if (changed.size() != n || prev.scored.size() != n || material_now.size() != n || (prev.at_same_point && prev.material.size() != n) ||
        now.components > 4)
        throw std::runtime_error("mark_changes: the images differ in size");
    double before[4];
    for (size_t i = 0; i < now.pixels.size(); ++i) {
        const size_t p = now.pixels[i];
        if (changed[p] || !previous_value(prev, p, position, material_now, w, h, now.components, before)) continue;
        for (int k = 0; k < now.components; ++k)
            if (std::abs(now.target[i * now.components + k] - before[k]) > tau) changed[p] = 1;
    }
}

RegionMap classify_regions(const RegionFrame& g, const CheckpointTarget& now, const std::vector<uint8_t>& changed, const RegionThresholds& t) {
    const size_t n = (size_t)g.width * g.height;
    if (g.material.size() != n || g.depth.size() != n || changed.size() != n || (!g.mask.empty() && g.mask.size() != n) ||
        (!g.age.empty() && g.age.size() != n))
        throw std::runtime_error("classify_regions: the frame's images differ in size");
    const std::vector<uint8_t> edge = rrc_host::dilate_chebyshev(edge_seeds(g, t.depth_jump), g.width, g.height, t.edge_radius);
    RegionMap m;
    for (size_t i = 0; i < now.pixels.size(); ++i) {
        const size_t p = now.pixels[i];
        uint8_t bits = 0;
        if (g.material[p] == t.object_material) bits |= 1u << kRegionObject;
        if (edge[p]) bits |= 1u << kRegionEdge;
        if (!g.age.empty() && g.age[p] < t.young_age) bits |= 1u << kRegionYoung;
        if (changed[p]) bits |= 1u << kRegionChanged;
        uint8_t region = kRegionStatic;
        for (int r = 0; r < kRegionStatic; ++r)
            if (bits & (1u << r)) {
                region = (uint8_t)r;
                break;
            }
        if (region == kRegionStatic) bits |= 1u << kRegionStatic;
        m.region.push_back(region);
        m.bits.push_back(bits);
    }
    return m;
}

RegionParts decompose(const Ensemble& e, const std::vector<CheckpointTarget>& targets, const std::vector<RegionMap>& maps) {
    RegionParts parts;
    if (maps.size() != e.checkpoints() || targets.size() != e.checkpoints())
        throw std::runtime_error("decompose: one region map and one target per checkpoint");
    for (size_t c = 0; c < e.checkpoints(); ++c) {
        const CheckpointTarget& t = targets[c];
        const RegionMap& m = maps[c];
        const std::vector<double>&sum = e.sum(c), &sum_sq = e.sum_sq(c);
        const double S = e.seeds(c);
        if (S < 2) throw std::runtime_error("an ensemble needs at least 2 seeds at every checkpoint");
        if (m.region.size() != t.pixels.size() || sum.size() != t.target.size())
            throw std::runtime_error("decompose: the region map does not match the checkpoint's pixels");
        const double values = (double)t.target.size(), pixels = (double)t.pixels.size();
        for (size_t i = 0; i < t.pixels.size(); ++i) {
            const int r = m.region[i];
            parts.pixel_share[r] += 1.0 / pixels;
            for (int k = 0; k < kRegionCount; ++k)
                if (m.bits[i] & (1u << k)) parts.raw_share[k] += 1.0 / pixels;
            for (int k = 0; k < t.components; ++k) {
                // Ensemble::metrics's terms, value by value: each value's share of the mean over values.
                const size_t v = i * t.components + k;
                const double mean = sum[v] / S, err = mean - t.target[v];
                const double var = std::max(sum_sq[v] - S * mean * mean, 0.0) / (S - 1.0);
                parts.bias2[r] += (err * err - var / S - t.noise) / values;
                parts.variance[r] += var / values;
            }
        }
        ++parts.checkpoints;
    }
    if (parts.checkpoints)
        for (int r = 0; r < kRegionCount; ++r) {
            parts.pixel_share[r] /= parts.checkpoints, parts.raw_share[r] /= parts.checkpoints;
            parts.bias2[r] /= parts.checkpoints, parts.variance[r] /= parts.checkpoints;
        }
    return parts;
}

std::vector<float> bias_map(const Ensemble& e, size_t c, const CheckpointTarget& t, size_t pixel_count) {
    std::vector<float> map(pixel_count, std::numeric_limits<float>::quiet_NaN());
    const std::vector<double>& sum = e.sum(c);
    const double S = e.seeds(c);
    if (sum.size() != t.target.size() || S < 1) return map;
    for (size_t i = 0; i < t.pixels.size(); ++i) {
        double b = 0.0;
        for (int k = 0; k < t.components; ++k) b += sum[i * t.components + k] / S - t.target[i * t.components + k];
        map.at(t.pixels[i]) = (float)(b / t.components);
    }
    return map;
}

std::vector<uint8_t> region_image(const RegionMap& m, const CheckpointTarget& t, size_t pixel_count) {
    std::vector<uint8_t> img(pixel_count, kRegionUnscored);
    for (size_t i = 0; i < t.pixels.size(); ++i) img.at(t.pixels[i]) = m.region[i];
    return img;
}

std::vector<uint16_t> next_age(const std::vector<uint16_t>& before, const std::vector<uint8_t>& mask, const float* prev_clip, uint32_t w,
                               uint32_t h, uint32_t cap) {
    std::vector<uint16_t> age(mask.size(), 1);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t p = (size_t)y * w + x;
            if (mask[p] & kMaskBackground) {
                age[p] = 0;
            } else if ((mask[p] & kMaskHit) && !before.empty() && prev_clip[p * 4 + 3] > 0.0f) {
                const float* c = &prev_clip[p * 4];
                const int qx = std::clamp((int)std::floor((c[0] / c[3] + 1.0f) * 0.5f * w), 0, (int)w - 1);
                const int qy = std::clamp((int)std::floor((c[1] / c[3] + 1.0f) * 0.5f * h), 0, (int)h - 1);
                age[p] = (uint16_t)std::min<uint32_t>(before[(size_t)qy * w + qx] + 1u, cap);
            }
        }
    return age;
}

}  // namespace rrc_sweep
