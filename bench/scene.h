// Deterministic frame inputs for the bench: a ground plane and two spheres
// seen by a camera that moves a little sideways between two poses.  Frames
// alternate pose 0, 1, 0, 1, ... and each one's reprojection data points at
// the other pose, so every frame is exactly consistent with the previous
// one and the hit/miss mix is that of a real frame: most pixels hit, the
// sky is background, and the disoccluded strips beside the spheres miss.
#pragma once

#include "config.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rrc_bench {

constexpr float kNear = 0.1f, kFar = 100.0f;  // REVERSED depth, finite far (plain MOTION linearises with them)

struct PoseFrame {
    std::vector<float> depth;         // W*H, REVERSED NDC depth, sky = 0
    std::vector<float> reprojection;  // W*H*n, n = floats_per_pixel(source) (empty for CAMERA)
    std::vector<uint32_t> object_id;  // W*H (only with object ids): 0 sky, 1 plane, 2 and 3 the spheres
    glm::dmat4 view_proj{1.0}, prev_view_proj{1.0};
    glm::dvec3 eye{0.0}, prev_eye{0.0};  // the poses' eyes (rrc_frame_desc.camera_position, for the view lobe)
};

struct SceneInputs {
    uint32_t width = 0, height = 0;
    PoseFrame poses[2];
    std::vector<std::vector<float>> samples;     // per channel, W*H*components, uniform noise in [0,1)
    std::vector<std::vector<float>> confidence;  // per channel (empty without confidence), W*H in [0,1)
    std::vector<std::vector<float>> base;        // per channel (empty without residual), W*H*components in [0,1)
    std::vector<uint8_t> nocache;                // W*H, ~nocache_share set (only with nocache)
};

/** Floats per pixel of the standalone API's reprojection array: 4, 2, 3 or 0 (CAMERA). */
uint32_t floats_per_pixel(rrc_reprojection source);

SceneInputs make_scene(const Config& config);

}  // namespace rrc_bench
