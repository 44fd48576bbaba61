// Reprojection sources -> (uv_prev, expected previous depth e, clip w), each
// with the kernel's fp32 error bound (error_bound.h).
#ifndef RRC_REFERENCE_REPROJECT_H
#define RRC_REFERENCE_REPROJECT_H

#include <rrc/rrc.h>

#include <glm/glm.hpp>

#include "error_bound.h"
#include "params.h"

namespace rrc_ref {

// Per-frame CAMERA constants, formed in double: M = VP_prev * inverse(VP_cur)
// and r = row 3 of inverse(VP_cur).
struct Camera {
    glm::dmat4 m{1.0};
    glm::dvec4 r{0.0};
};
Camera make_camera(const rrc_frame_desc& frame);

struct Reprojected {
    Bounded uv_x, uv_y;
    Bounded e;  // expected previous depth (linear for LINEAR and plain MOTION)
    Bounded w;  // clip w of the previous position (1 for motion vectors)
    // CAMERA on NDC depth: the ADAPTIVE test's allowance for the fp32 error of
    // e (docs/CONVENTIONS.md), CAMERA_ULPS * 2^-24 * sum_k |M_2k v_k| / |w|; else 0.
    double camera_err = 0.0;
};

// Whether the pixel's per-pixel reprojection data are all finite.
bool reprojection_data_finite(const Params& p, const rrc_frame_desc& frame, size_t pixel);

// Pixel (i, j) with current depth d (not background, not invalid).
Reprojected reproject(const Params& p, const rrc_frame_desc& frame, const Camera& cam, int i, int j, double d);

}  // namespace rrc_ref

#endif
