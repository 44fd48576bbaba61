// The bilinear taps of the previous-depth fetch, docs/CONVENTIONS.md
// (Coordinates and jitter): q = uv_prev * size - prev_jitter, p = q - 0.5,
// i0 = floor(p), f = p - i0; taps i0, i0 + (1,0), i0 + (0,1), i0 + (1,1), each
// clamped to the image per axis, weights (1-fx)(1-fy), fx(1-fy), (1-fx)fy, fx fy.
// One definition for every evaluator of the scenes (false_hits.h,
// visibility.h) and the self-tests' epsilon test, so they cannot disagree on
// which texels a pixel reads.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <glm/glm.hpp>

namespace rrc_scene {

struct BilinearTaps {
    int x[4], y[4];    // texel column and row, clamped
    double weight[4];  // in the order above; they sum to 1

    size_t index(int t, int width) const { return static_cast<size_t>(y[t]) * width + x[t]; }
};

// `pixel` is uv_prev * size (the continuous pixel coordinate of the
// reprojected point, texel centres at i + 0.5 before the jitter).
inline BilinearTaps bilinear_taps(const glm::dvec2& pixel, const glm::dvec2& prev_jitter, int width, int height) {
    const glm::dvec2 p = pixel - prev_jitter - 0.5;
    const glm::dvec2 p0 = glm::floor(p), f = p - p0;
    BilinearTaps taps;
    for (int t = 0; t < 4; ++t) {
        taps.x[t] = std::clamp(static_cast<int>(p0.x) + (t & 1), 0, width - 1);
        taps.y[t] = std::clamp(static_cast<int>(p0.y) + (t >> 1), 0, height - 1);
        taps.weight[t] = ((t & 1) ? f.x : 1.0 - f.x) * ((t >> 1) ? f.y : 1.0 - f.y);
    }
    return taps;
}

}  // namespace rrc_scene
