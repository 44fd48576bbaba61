#include "frame_constants.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace rrc {

FramePushConstants make_frame_constants(const ContextConfig& c, const Frame& f, bool prev_valid) {
    FramePushConstants pc{};
    if (c.reprojection == RRC_REPROJECTION_CAMERA) {
        // M = VP_prev * VP_cur^-1 in double; only the product is rounded to fp32.
        glm::dmat4 vp = glm::make_mat4(f.view_proj);
        glm::dmat4 vp_prev = glm::make_mat4(f.prev_view_proj);
        glm::dmat4 inv = glm::inverse(vp);
        glm::dmat4 m = vp_prev * inv;
        for (int col = 0; col < 4; ++col)
            for (int row = 0; row < 4; ++row) pc.M[col * 4 + row] = (float)m[col][row];
        for (int col = 0; col < 4; ++col) pc.inv_row3[col] = (float)inv[col][3];  // row 3 of VP_cur^-1
    }
    pc.jitter[0] = f.jitter[0];
    pc.jitter[1] = f.jitter[1];
    pc.jitter[2] = f.prev_jitter[0];
    pc.jitter[3] = f.prev_jitter[1];
    pc.motion_scale[0] = c.motion_scale[0];
    pc.motion_scale[1] = c.motion_scale[1];
    pc.eps = c.epsilon_value;
    pc.near_plane = c.near_plane;
    pc.far_plane = c.far_plane;
    pc.bg_threshold = c.background_threshold;
    pc.prev_valid = prev_valid && !f.reset ? 1u : 0u;
    // The refresh clock in 64-bit: the kernel sees only t mod n (docs/CONVENTIONS.md, "Refresh policies").
    pc.refresh_phase = (uint32_t)(f.frame_index % c.refresh_period);
    return pc;
}

ViewBuffer make_view_buffer(const Frame& f) {
    // In double, relative to the eye, so the fp32 result keeps the digits of
    // P - C even far from the world origin (docs/CONVENTIONS.md, "The view-dependent history").
    const glm::dvec3 C = glm::make_vec3(f.camera_position), C_prev = glm::make_vec3(f.prev_camera_position);
    const glm::dmat4 Q = glm::translate(glm::dmat4(1.0), -C) * glm::inverse(glm::make_mat4(f.view_proj));
    ViewBuffer v{};
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) v.Q[col * 4 + row] = (float)Q[col][row];
    const glm::dvec3 d = C_prev - C;
    for (int k = 0; k < 3; ++k) v.d[k] = (float)d[k];
    v.d[3] = f.lighting_turn;  // phi, added to every pixel's view turn
    return v;
}

}  // namespace rrc
