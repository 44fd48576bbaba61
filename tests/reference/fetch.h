// Texel fetches of the previous frame at sample coordinate q (texel centres
// at integer + 0.5, q = uv_prev * size - prev_jitter): nearest, bilinear,
// Catmull-Rom clamped to the bilinear taps, and the bounded depth fetch.
#ifndef RRC_REFERENCE_FETCH_H
#define RRC_REFERENCE_FETCH_H

#include <rrc/rrc.h>

#include <cstdint>
#include <vector>

#include "error_bound.h"
#include "params.h"

namespace rrc_ref {

// clamp(floor(q), 0, size - 1); q must not be NaN.
int nearest_index(double q, int size);

// One image of `components` interleaved floats per texel.
struct Image {
    const float* data;
    int width, height;
    unsigned components;
    double at(int x, int y, unsigned c) const;  // clamps x, y to the edge
};

// Resamples every component at (qx, qy) with the filter; out[c] for c < components.
// blur_g: GAUSSIAN's g = blur_sigma^2 / 2 (ignored by the other filters).
void resample(const Image& img, rrc_history_filter filter, double qx, double qy, double* out, double blur_g = 0.125);

// The four bilinear taps at q (docs/CONVENTIONS.md, "Coordinates and jitter"):
// the cell's top-left corner (x0, y0) before the clamp, each tap clamped to the
// image, in the order (x0, y0), (x0+1, y0), (x0, y0+1), (x0+1, y0+1), with the
// weights (1-fx)(1-fy), fx(1-fy), (1-fx)fy, fx fy.
struct BilinearTaps {
    int x0, y0;
    int x[4], y[4];
    double w[4];
};
BilinearTaps bilinear_taps(double qx, double qy, int width, int height);

struct DepthFetch {
    Bounded value;           // fetched previous depth (NDC z, or linear d for LINEAR)
    Decision no_background;  // none of the four taps is background
};

// The bilinear previous-depth fetch of the hit test.  qx, qy carry the
// kernel's position error; `scale` multiplies the error bounds it uses for
// its own decisions (Options::error_scale).
DepthFetch fetch_depth(const Params& p, const std::vector<float>& depth, Bounded qx, Bounded qy, double scale);

// Object ids (docs/CONVENTIONS.md "Previous depth fetch and the hit test"): every bilinear tap whose
// weight is not zero holds `id`.  Unsure where the kernel's position error
// could move a foreign tap's weight across zero or change the cell.
Decision taps_hold_id(const std::vector<uint32_t>& ids, int width, int height, Bounded qx, Bounded qy, uint32_t id, double scale);

}  // namespace rrc_ref

#endif
