// The kernel-vs-reference value tolerance, in one place (docs/measurements/ACCURACY.md):
//   |kernel - reference| <= 1e-6 + 1e-5 |r|          (filter arithmetic, fp32)
//                          + one fp16 step at |r|     (fp16 history only)
//                          + 4 * S * 2^-24 * max(W,H) (sample position)
// where S is the spread of the previous history over the 4x4 texels around
// the reprojected position: the fp32 sample position is only resolved to
// about ulp(max(W,H)) texels, and the resampled history moves with it.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace rrc_test {

// Allowed error from the sample position, in units of spread x coordinate
// resolution; the measured maxima are 0.65 (docs/measurements/ACCURACY.md).
constexpr double kPositionFactor = 4.0;

inline double fp16_step(double v) {
    double a = std::fabs(v);
    if (a < std::ldexp(1.0, -14)) return std::ldexp(1.0, -24);
    return std::ldexp(1.0, (int)std::floor(std::log2(a)) - 10);
}

// fp32 resolution of a texel coordinate in a W x H image, in texels.
inline double coordinate_resolution(int W, int H) { return std::ldexp(1.0, -24) * std::max(W, H); }

// Spread (max - min) of component q of the previous history over the 4x4
// texels around the reprojected position uv (previous jitter pj).
inline double history_spread(const std::vector<float>& hist, unsigned comps, unsigned q, int W, int H, double uvx, double uvy,
                             const float* pj) {
    if (!std::isfinite(uvx) || !std::isfinite(uvy) || hist.empty()) return 0.0;
    double px = uvx * W - pj[0] - 0.5, py = uvy * H - pj[1] - 0.5;
    int x0 = (int)std::floor(px), y0 = (int)std::floor(py);
    double lo = INFINITY, hi = -INFINITY;
    for (int y = y0 - 1; y <= y0 + 2; ++y)
        for (int x = x0 - 1; x <= x0 + 2; ++x) {
            int cx = std::min(std::max(x, 0), W - 1), cy = std::min(std::max(y, 0), H - 1);
            double v = hist[comps * ((size_t)cy * W + cx) + q];
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    return hi - lo;
}

// The arithmetic part of the tolerance (without the position term).
inline double arithmetic_tolerance(double reference, double reference_exact, bool fp16) {
    return 1e-6 + 1e-5 * std::fabs(reference) + (fp16 ? fp16_step(reference_exact) : 0.0);
}

inline double position_tolerance(double spread, int W, int H) { return kPositionFactor * spread * coordinate_resolution(W, H); }

}  // namespace rrc_test
