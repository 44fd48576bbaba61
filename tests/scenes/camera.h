// Camera path and Vulkan-convention projection of the analytic scenes.
//
// View space is right-handed: x right, y up, the camera looks down -z.  The
// projection maps it to Vulkan clip space by hand (no GLM helpers, so no
// GLM_FORCE_* macro can change it):
//   x_clip =  x_v / (aspect * tan(fovy/2))
//   y_clip = -y_v / tan(fovy/2)              (y flipped: NDC y points down)
//   w_clip = -z_v = d                        (planar view depth)
//   z_clip = za * d + zb, so NDC z = za + zb / d, with
//     STANDARD, far finite:   za = f/(f-n),  zb = -n f/(f-n)   (z(n)=0, z(f)=1)
//     STANDARD, far = +inf:   za = 1,        zb = -n
//     REVERSED, far finite:   za = -n/(f-n), zb =  n f/(f-n)   (z(n)=1, z(f)=0)
//     REVERSED, far = +inf:   za = 0,        zb =  n           (z = n/d)
//     LINEAR:                 as STANDARD (the depth buffer holds d = w_clip;
//                             z only fills the clip vectors and matrices).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace rrc_scene {

struct CameraPose {
    glm::dvec3 eye{0.0};
    // Camera-to-world rotation; columns are the view axes right (+x_v),
    // up (+y_v) and back (+z_v, opposite to the viewing direction).
    glm::dmat3 basis{1.0};

    glm::dmat4 view_matrix() const;  // world -> view
};

// Pose at time t (frames).  The path orbits the scene centre (about 0.6
// degrees a frame at speed 1), bobs up and down, drifts its target and rolls
// slightly: translation and rotation at once.
CameraPose camera_pose(double t, double speed);

// A low camera grazing the ground (y = 0): it orbits at radius 8 and height
// ~1.5 without roll, pitched down just so far that the top corners of the
// image, its rays closest to the horizon, meet the ground at
// `max_ground_angle_degrees` from its normal.  Every ground pixel is then seen
// at up to that angle and no sky shows: the regime where one pixel covers a
// long stretch of ground and depth changes fastest across it.
CameraPose grazing_camera_pose(double t, double speed, double fovy_degrees, double aspect, double max_ground_angle_degrees);

struct Projection {
    uint32_t depth_mode = 0;  // RRC_DEPTH_MODE_*
    double near_plane = 0.1;
    double far_plane = 100.0;  // may be +inf
    double tan_half_fovy = 0.0;
    double aspect = 1.0;        // width / height: square pixels
    double za = 0.0, zb = 0.0;  // NDC z = za + zb / d
    glm::dmat4 matrix{1.0};     // view -> Vulkan clip, column-major

    double ndc_z(double d) const { return za + zb / d; }
};

Projection make_projection(uint32_t depth_mode, double near_plane, double far_plane, double fovy_degrees, double aspect);

}  // namespace rrc_scene
