// Everything that changes per frame, computed on the CPU: the camera and
// light matrices of this frame and the previous one, each object's current
// and previous model matrix, the area light's sample point, the rotated
// Poisson pattern.  FrameUniforms/GpuObject mirror shaders/common.glsl.
#pragma once

#include "scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rrc_sample {

constexpr int kMaxTaps = 64;

/** std140; the layout of shaders/common.glsl's FrameUniforms. */
struct FrameUniforms {
    glm::mat4 view_proj;       // current, Vulkan clip (y down, reversed z)
    glm::mat4 prev_view_proj;  // previous frame's
    glm::mat4 inv_view_proj;
    glm::mat4 sun_vp;             // sun's orthographic shadow map
    glm::mat4 lamp_point_vp;      // this frame's random point on the area light
    glm::mat4 lamp_centre_vp;     // the area light's centre (PCSS fallback)
    glm::vec4 camera_pos;         // w: time in seconds
    glm::vec4 sun_dir;            // towards the sun; w: normal offset (world units)
    glm::vec4 sun_colour;         // w: PCF radius in sun-map texels
    glm::vec4 ambient;            // w: sun-map depth bias (world units)
    glm::vec4 lamp_centre;        // w: lamp maps' near plane
    glm::vec4 lamp_u;             // half axis; w: far plane
    glm::vec4 lamp_v;             // half axis; w: tan(fov / 2)
    glm::vec4 lamp_point;         // this frame's point; w: lamp map size (texels)
    glm::vec4 lamp_facing;        // w: relative depth bias
    glm::vec4 lamp_colour;        // w: sun map size (texels)
    glm::vec4 sphere;             // mirror sphere centre, radius
    glm::vec4 bump;               // x: bump frequency (1/m), y: strength, z: the environment map's turn (radians, Scene::light_angle)
    glm::vec4 mirror_eye;         // w 1: the eye the mirror sphere reflects for (Scene::frozen_mirror_view); w 0: the camera's
    glm::uvec4 frame;             // x: frame index, y: taps k, z: width, w: height
    glm::vec4 poisson[kMaxTaps];  // xy: the k-tap pattern in the unit disk
};
static_assert(sizeof(FrameUniforms) == 6 * 64 + 14 * 16 + kMaxTaps * 16, "std140 layout");

/** std430; shaders/common.glsl's ObjectData. */
struct GpuObject {
    glm::mat4 model;
    glm::mat4 prev_model;
    glm::vec4 albedo;
    glm::uvec4 material;  // x: Material
};

struct RenderSettings {
    uint32_t width = 256, height = 160;
    int taps = 4;
    float fps = 30.0f;
    uint32_t sun_map = 512, lamp_map = 512;
    float pcf_radius = 3.0f;   // sun-map texels
    uint32_t seed = 0;         // ensemble member: moves every random stream (0: the sample's own)
    uint32_t pcf_pattern = 0;  // 0 the uniform disk (unbiased for the exact target), 1 the paper's rotated Poisson disk
    uint32_t env_base = 0;     // the env residual's base (Sampling::env_base): 0 none, 1 centre sample, 2 unbumped
    uint32_t pcf_base = 0;     // the pcf residual's base (SignalPasses::record_pcf_base): its bilinear taps, 0 none
};

struct FrameState {
    FrameUniforms uniforms;
    std::vector<GpuObject> objects;
    glm::dmat4 view_proj, prev_view_proj;  // for rrc's CAMERA source
    glm::dvec3 eye, prev_eye;              // the camera's positions, for rrc's view lobe (rrc_frame_desc.camera_position)
    float lighting_turn = 0.0f;            // radians the environment map turned since the previous frame (rrc_frame_desc.lighting_turn)
};

/** The state of frame `index` (time index / fps); frame 0's "previous" is itself. */
FrameState make_frame_state(const Scene& scene, const RenderSettings& settings, int index);

/** Reversed-z perspective with a finite far plane, Vulkan clip (y down). */
glm::mat4 reversed_perspective(float fov_y, float aspect, float near_plane, float far_plane);
/** The area light's perspective (standard depth) from `point`. */
glm::mat4 lamp_view_proj(const AreaLight& lamp, glm::vec3 point);
/** Point `index` of the R2 low-discrepancy sequence on the light (the per-frame sample point),
 *  toroidally shifted by a random offset drawn from `seed` (0: no shift), so each point's
 *  marginal over seeds is uniform on the light. */
glm::vec3 lamp_sequence_point(const AreaLight& lamp, int index, uint32_t seed = 0);
/** The soft signal's k light points of frame `index`: sequence points index*k .. index*k + k - 1. */
std::vector<glm::vec3> lamp_frame_points(const AreaLight& lamp, int index, int k, uint32_t seed);
/** Points j of the m x m midpoint grid on the light (the soft-shadow reference), m*m >= count. */
glm::vec3 lamp_grid_point(const AreaLight& lamp, int j, int count);
/** k points in the unit disk, well spread (best candidate, fixed seed). */
std::vector<glm::vec2> poisson_disk(int k);

}  // namespace rrc_sample
