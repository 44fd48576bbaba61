// The cache hit test of one pixel against the previous depth buffer, with
// the certainty of each comparison under the kernel's fp32 error.
#ifndef RRC_REFERENCE_HIT_TEST_H
#define RRC_REFERENCE_HIT_TEST_H

#include <cstdint>
#include <vector>

#include "error_bound.h"
#include "params.h"
#include "reproject.h"

namespace rrc_ref {

struct HitTest {
    Decision hit;                                                 // w > 0, uv_prev in [0,1]^2, no background tap, |diff| <= eps
    Bounded qx, qy;                                               // previous-frame sample coordinate uv_prev * size - prev_jitter
    double diff = NAN, eps = NAN, diff_err = NAN, fetched = NAN;  // NaN: not computed
};

// The current pixel (i, j) and the frame's arrays the ADAPTIVE test and the
// object-id rule read.
struct CurrentPixel {
    const float* depth;  // the frame's depth, W*H
    int i, j;
    const uint32_t* object_id;              // the frame's ids (object-id contexts), else NULL
    const std::vector<uint32_t>* prev_ids;  // the previous frame's ids (object-id contexts)
};

// For a pixel that may hit (previous frame valid, geometry valid, cacheable).
// `scale` is Options::error_scale.
HitTest hit_test(const Params& p, const std::vector<float>& prev_depth, const float prev_jitter[2], const Reprojected& r,
                 const CurrentPixel& cur, double scale);

}  // namespace rrc_ref

#endif
