#include "clean_regions.h"

#include <rrc/rrc.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rrc_host {
namespace {

/** Where an edge starts: the background, a jump of u (inverse_depth_jump) or another object id
 *  among the four neighbours. */
std::vector<uint8_t> edge_seeds(const CleanFrame& f) {
    const uint32_t w = f.width, h = f.height;
    std::vector<uint8_t> seed((size_t)w * h, 0);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t p = (size_t)y * w + x;
            bool s = (f.mask[p] & RRC_MASK_BACKGROUND) != 0;
            if (f.inverse_depth) s = s || !(f.inverse_depth[p] > 0.0f) || inverse_depth_jump(f.inverse_depth, w, h, x, y, kCleanDepthJump);
            if (f.object_id && !s) {
                const uint32_t id = f.object_id[p];
                s = (x > 0 && f.object_id[p - 1] != id) || (x + 1 < w && f.object_id[p + 1] != id) ||
                    (y > 0 && f.object_id[p - w] != id) || (y + 1 < h && f.object_id[p + w] != id);
            }
            seed[p] = s ? 1 : 0;
        }
    return seed;
}

}  // namespace

std::vector<uint8_t> dilate_chebyshev(const std::vector<uint8_t>& in, uint32_t w, uint32_t h, int radius) {
    std::vector<uint8_t> rows(in.size(), 0), out(in.size(), 0);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            if (!in[(size_t)y * w + x]) continue;
            for (int dx = -radius; dx <= radius; ++dx) {
                const int xx = (int)x + dx;
                if (xx >= 0 && xx < (int)w) rows[(size_t)y * w + xx] = 1;
            }
        }
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            if (!rows[(size_t)y * w + x]) continue;
            for (int dy = -radius; dy <= radius; ++dy) {
                const int yy = (int)y + dy;
                if (yy >= 0 && yy < (int)h) out[(size_t)yy * w + x] = 1;
            }
        }
    return out;
}

bool inverse_depth_jump(const float* u, uint32_t w, uint32_t h, uint32_t x, uint32_t y, float jump) {
    const size_t p = (size_t)y * w + x;
    const float tau = jump * u[p];
    if (x > 0 && x + 1 < w && std::abs(u[p - 1] - 2.0f * u[p] + u[p + 1]) > tau) return true;
    return y > 0 && y + 1 < h && std::abs(u[p - w] - 2.0f * u[p] + u[p + w]) > tau;
}

std::string clean_number(double v, const char* fmt) {
    char b[64];
    std::snprintf(b, sizeof b, fmt, v);
    return b;
}

const char* clean_region_name(int r) {
    static const char* const names[kCleanRegionCount] = {"background", "edge", "filled", "miss", "young", "history"};
    return r >= 0 && r < kCleanRegionCount ? names[r] : "all";
}

float clean_inverse_depth(uint32_t mode, float z) {
    if (!std::isfinite(z)) return 0.0f;
    if (mode == RRC_DEPTH_MODE_LINEAR) return z > 0.0f ? 1.0f / z : 0.0f;
    if (mode == RRC_DEPTH_MODE_REVERSED) return z;
    return 1.0f - z;  // STANDARD: 1 - z is proportional to 1/w up to 1/far
}

std::vector<uint8_t> clean_regions(const CleanFrame& f) {
    if (!f.mask || !f.age) throw std::invalid_argument("clean_regions: the mask and the age are required");
    const std::vector<uint8_t> edge = dilate_chebyshev(edge_seeds(f), f.width, f.height, kCleanEdgeRadius);
    const uint32_t young = f.fill_age ? f.fill_age : kCleanYoungAge;
    std::vector<uint8_t> region(edge.size());
    for (size_t p = 0; p < region.size(); ++p) {
        const uint8_t m = f.mask[p];
        if (m & RRC_MASK_BACKGROUND)
            region[p] = kCleanBackground;
        else if (edge[p])
            region[p] = kCleanEdge;
        else if (f.fill_age && f.age[p] < f.fill_age)
            region[p] = kCleanFilled;
        else if (!(m & RRC_MASK_HIT))
            region[p] = kCleanMiss;
        else if (f.age[p] < young)
            region[p] = kCleanYoung;
        else
            region[p] = kCleanHistory;
    }
    return region;
}

void CleanSums::add(const CleanSums& o) {
    for (int r = 0; r < kCleanRegionCount; ++r) sse[r] += o.sse[r], pixels[r] += o.pixels[r], values[r] += o.values[r];
    skipped += o.skipped;
}

double CleanSums::total_sse() const {
    double s = 0.0;
    for (double v : sse) s += v;
    return s;
}
uint64_t CleanSums::total_pixels() const {
    uint64_t s = 0;
    for (uint64_t v : pixels) s += v;
    return s;
}
uint64_t CleanSums::total_values() const {
    uint64_t s = 0;
    for (uint64_t v : values) s += v;
    return s;
}
double CleanSums::rmse(int r) const {
    const double e = r == kCleanRegionCount ? total_sse() : sse[r];
    const uint64_t n = r == kCleanRegionCount ? total_values() : values[r];
    return n ? std::sqrt(e / (double)n) : 0.0;
}

void add_clean_errors(CleanSums& s, const std::vector<uint8_t>& regions, const float* in, const float* out, int stride, int components,
                      const uint8_t* scored) {
    for (size_t p = 0; p < regions.size(); ++p) {
        if (scored && !scored[p]) continue;
        double e = 0.0;
        bool finite = true;
        for (int c = 0; c < components; ++c) {
            const float a = in[p * stride + c], b = out[p * stride + c];
            finite = finite && std::isfinite(a) && std::isfinite(b);
            e += ((double)b - a) * ((double)b - a);
        }
        if (!finite) {
            ++s.skipped;
            continue;
        }
        const int r = regions[p];
        s.sse[r] += e;
        s.pixels[r] += 1;
        s.values[r] += (uint64_t)components;
    }
}

std::string clean_table(const CleanSums& s) {
    const double sse = s.total_sse(), pixels = (double)s.total_pixels();
    std::string t = "| region | RMSE | share of squared error | share of pixels |\n|---|---|---|---|\n";
    for (int r = 0; r <= kCleanRegionCount; ++r) {
        const double e = r == kCleanRegionCount ? sse : s.sse[r];
        const double n = r == kCleanRegionCount ? pixels : (double)s.pixels[r];
        t += std::string("| ") + (r == kCleanRegionCount ? "all" : clean_region_name(r)) + " | " + clean_number(s.rmse(r), "%.4g") + " | " +
             (sse > 0 ? clean_number(100.0 * e / sse, "%.1f%%") : std::string("-")) + " | " +
             (pixels > 0 ? clean_number(100.0 * n / pixels, "%.1f%%") : std::string("-")) + " |\n";
    }
    return t;
}

std::string clean_csv_rows(const std::string& prefix, const CleanSums& s) {
    std::string t;
    for (int r = 0; r <= kCleanRegionCount; ++r) {
        const bool all = r == kCleanRegionCount;
        t += prefix + "," + clean_region_name(r) + "," + std::to_string(all ? s.total_pixels() : s.pixels[r]) + "," +
             std::to_string(all ? s.total_values() : s.values[r]) + "," + clean_number(all ? s.total_sse() : s.sse[r], "%.9g") + "," +
             clean_number(s.rmse(r), "%.6g") + "\n";
    }
    return t;
}

}  // namespace rrc_host
