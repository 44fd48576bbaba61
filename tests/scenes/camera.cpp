// Camera path and projection matrices (see camera.h for the exact formulas).
#include "scenes/camera.h"

#include <cmath>

#include "rrc/rrc.h"

namespace rrc_scene {

glm::dmat4 CameraPose::view_matrix() const {
    // Inverse of the rigid camera-to-world transform: R^T (p - eye).
    const glm::dmat3 rt = glm::transpose(basis);
    glm::dmat4 v(rt);
    v[3] = glm::dvec4(-(rt * eye), 1.0);
    return v;
}

CameraPose camera_pose(double t, double speed) {
    const double s = t * speed;
    const double theta = 0.35 + 0.01 * s;
    CameraPose pose;
    pose.eye = glm::dvec3(12.0 * std::sin(theta), 4.0 + 0.5 * std::sin(0.03 * s), 12.0 * std::cos(theta));
    const glm::dvec3 target(0.3 * std::sin(0.02 * s), 0.8, 0.5);
    const glm::dvec3 back = glm::normalize(pose.eye - target);
    const glm::dvec3 right0 = glm::normalize(glm::cross(glm::dvec3(0.0, 1.0, 0.0), back));
    const glm::dvec3 up0 = glm::cross(back, right0);
    // Roll about the viewing axis so the rotation is not only yaw and pitch.
    const double roll = 0.05 * std::sin(0.02 * s);
    const double c = std::cos(roll), sn = std::sin(roll);
    const glm::dvec3 right = c * right0 + sn * up0;
    const glm::dvec3 up = -sn * right0 + c * up0;
    pose.basis = glm::dmat3(right, up, back);
    return pose;
}

CameraPose grazing_camera_pose(double t, double speed, double fovy_degrees, double aspect, double max_ground_angle_degrees) {
    const double s = t * speed;
    const double theta = 0.35 + 0.01 * s;
    CameraPose pose;
    pose.eye = glm::dvec3(8.0 * std::sin(theta), 1.5 + 0.1 * std::sin(0.03 * s), 8.0 * std::cos(theta));
    const glm::dvec3 target(0.3 * std::sin(0.02 * s), 0.0, 0.5);
    glm::dvec3 ahead = target - pose.eye;
    ahead.y = 0.0;
    ahead = glm::normalize(ahead);
    const glm::dvec3 right = glm::normalize(glm::cross(ahead, glm::dvec3(0.0, 1.0, 0.0)));
    // The top corner ray in view space is (aspect*tn, tn, -1).  Pitched down
    // by b its world height is tn*cos(b) - sin(b) and its horizontal length
    // hypot(aspect*tn, tn*sin(b) + cos(b)); its elevation falls as b grows, so
    // bisect b for elevation -(90 deg - max angle).
    const double deg = 3.14159265358979323846 / 180.0;
    const double tn = std::tan(0.5 * fovy_degrees * deg);
    const double want = -(90.0 - max_ground_angle_degrees) * deg;
    double lo = 0.0, hi = 0.5 * 3.14159265358979323846;
    for (int k = 0; k < 80; ++k) {
        const double b = 0.5 * (lo + hi);
        const double elevation = std::atan2(tn * std::cos(b) - std::sin(b), std::hypot(aspect * tn, tn * std::sin(b) + std::cos(b)));
        (elevation > want ? lo : hi) = b;
    }
    const double b = 0.5 * (lo + hi);
    const glm::dvec3 forward = std::cos(b) * ahead - std::sin(b) * glm::dvec3(0.0, 1.0, 0.0);
    const glm::dvec3 up = glm::cross(right, forward);
    pose.basis = glm::dmat3(right, up, -forward);
    return pose;
}

Projection make_projection(uint32_t depth_mode, double n, double f, double fovy_degrees, double aspect) {
    Projection p;
    p.depth_mode = depth_mode;
    p.near_plane = n;
    p.far_plane = f;
    p.tan_half_fovy = std::tan(0.5 * fovy_degrees * 3.14159265358979323846 / 180.0);
    p.aspect = aspect;
    const bool infinite = std::isinf(f);
    if (depth_mode == RRC_DEPTH_MODE_REVERSED) {
        p.za = infinite ? 0.0 : -n / (f - n);
        p.zb = infinite ? n : n * f / (f - n);
    } else {  // STANDARD, and LINEAR's clip z
        p.za = infinite ? 1.0 : f / (f - n);
        p.zb = infinite ? -n : -n * f / (f - n);
    }
    glm::dmat4 m(0.0);  // m[column][row]
    m[0][0] = 1.0 / (aspect * p.tan_half_fovy);
    m[1][1] = -1.0 / p.tan_half_fovy;
    m[2][2] = -p.za;  // z_clip = za * (-z_v) + zb
    m[3][2] = p.zb;
    m[2][3] = -1.0;  // w_clip = -z_v
    p.matrix = m;
    return p;
}

}  // namespace rrc_scene
