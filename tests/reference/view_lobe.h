// The view-dependent history's age cap (docs/CONVENTIONS.md, "The
// view-dependent history"), in the manner of NVIDIA's NRD specular
// accumulation limited by parallax (REBLUR's ComputeParallax and
// GetSpecAccumSpeed).  Re-derived in double from that section, pinned by
// hand-computed self-tests; the kernel is validated against it.
#ifndef RRC_REFERENCE_VIEW_LOBE_H
#define RRC_REFERENCE_VIEW_LOBE_H

#include <rrc/rrc.h>

namespace rrc_ref {

struct Params;

// This frame's world position of a pixel from its sample position in NDC
// (x, y in [-1, 1], Vulkan depth z in [0, 1]) and inverse(VP_cur) (column
// major, as glm): X = inv_view_proj * (x, y, z, 1), P = X.xyz / X.w.
// Returns false where X.w is 0 or the result is not finite.
bool view_lobe_world_position(const double inv_view_proj[16], double x, double y, double z, double P[3]);

struct ViewLobe {
    double theta = 0.0;  // the angle between P - C and P - C_prev, radians in [0, pi]
    double r = 0.0;      // lobe / theta (+inf where theta = 0: nothing moved the view direction)
    unsigned age = 0;    // n_v = min(floor(r), n_prev)
    // The ages an fp32 theta within the bound of ViewTurn::err could give.
    unsigned age_lo = 0, age_hi = 0;
};

// The view turn at pixel (i, j) of depth d (docs/CONVENTIONS.md): its sample
// position (the centre plus this frame's jitter) and depth to P through
// inverse(view_proj) (LINEAR depth: the point of the pixel's ray whose clip w
// is d, as the CAMERA source), then theta between P - C and P - C_prev,
// plus the frame's lighting_turn phi (0.8).  The eyes' part is 0 where it is
// undefined (P not finite, on either eye) or below the fp32 normal range;
// err bounds the fp32 kernel's error of theta + phi.
struct ViewTurn {
    double theta = 0.0;
    double err = 0.0;
};
ViewTurn view_turn(const Params& p, const rrc_frame_desc& frame, int i, int j, double d);

// n_v = min(floor(alpha / theta), n_prev) from a view turn (theta = 0 caps
// nothing), with the ages theta +- err give.
ViewLobe view_lobe_cap(double lobe, const ViewTurn& turn, unsigned n_prev);

// The capped age n_v of a history of age n_prev >= 1 at the surface point P,
// seen this frame from C and the frame before from C_prev, for the channel's
// lobe > 0 (radians).  Where P coincides with either camera the view
// direction is undefined and nothing is capped (n_v = n_prev).
ViewLobe view_lobe_age(double lobe, const double P[3], const double C[3], const double C_prev[3], unsigned n_prev);

// The blend's lambda_eff after the cap: min(lambda_eff, n_v/(n_v + 1)) where
// n_v < n_prev, lambda_eff unchanged where n_v = n_prev (as the lag
// detector's n_a, docs/CONVENTIONS.md "The lag detector").
double view_lobe_lambda(double lambda_eff, unsigned n_prev, unsigned n_v);

}  // namespace rrc_ref

#endif
