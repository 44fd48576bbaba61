// The animated scenes: generated meshes placed in the world, their motion,
// the camera's flight path and the lights.  Pure CPU (GLM), no Vulkan.
#pragma once

#include "mesh.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace rrc_sample {

/** Material ids, written to the G-buffer (normal.w); shaders/common.glsl mirrors them. */
enum Material : uint32_t { kMatBackground = 0, kMatGround = 1, kMatStone = 2, kMatSphere = 3, kMatMover = 4 };
constexpr uint32_t kMaterialCount = 5;
/** "ground", "stone", "sphere", "torus" (and "background"). */
const char* material_name(uint32_t material);

/** The per-frame noisy signals the sample can produce, one rrc channel each. */
enum Signal : uint32_t { kSignalPcf = 1u, kSignalEnv = 2u, kSignalSoft = 4u };

struct SceneObject {
    uint32_t mesh = 0;
    uint32_t material = kMatStone;
    glm::mat4 base{1.0f};  // placement
    bool moves = false;    // animated by Scene::model()
};

struct Camera {
    glm::vec3 eye{0.0f}, target{0.0f};
    float fov_y = 0.87f;  // radians
};

/** A square area light: centre, two half axes, the direction it faces. */
struct AreaLight {
    glm::vec3 centre{0.0f}, half_u{1, 0, 0}, half_v{0, 0, 1}, facing{0, -1, 0};
    glm::vec3 colour{1.0f};
    float near_plane = 0.5f, far_plane = 40.0f, fov = 1.9f;  // its shadow maps' perspective
};

class Scene {
public:
    /** "temple" (all three signals) or "courtyard" (no mirror sphere: no env channel). */
    static Scene make(const std::string& name);
    static std::vector<std::string> names();

    std::string name;
    std::vector<MeshData> meshes;
    std::vector<SceneObject> objects;
    uint32_t signals = 0;  // the Signal bits this scene uses

    glm::vec3 sun_direction{0, 1, 0};  // towards the sun
    glm::vec3 sun_colour{1.0f};
    float sun_extent = 14.0f;  // half size of the sun's orthographic shadow map
    glm::vec3 ambient{0.1f};
    AreaLight lamp;
    glm::vec4 sphere{0, 1, 0, 1};  // the mirror sphere (analytic, for sub-pixel rays): centre, radius
    float near_plane = 0.1f, far_plane = 200.0f;

    /** Object `i`'s model matrix at time `t` seconds. */
    glm::mat4 model(size_t i, double t) const;
    Camera camera(double t) const;
    /** 0 = fixed camera (tests that want static pixels); 1 = the scene's flight. */
    float camera_speed = 1.0f;
    /** The moving light (rrc-sample and rrc-sweep --light-speed): degrees per frame that the sun and
     *  the environment map turn about the vertical (y) axis, counter-clockwise seen from above; 0 = the
     *  scene's fixed light.  The area lamp (soft shadows) does not move. */
    float light_speed = 0.0f;
    /** The frozen mirror view (rrc-sample --frozen-mirror-view): the mirror sphere reflects the
     *  environment as seen from camera(0)'s eye, whatever the camera does, so env's signal at a
     *  surface point no longer depends on the view: what is left of env's error under camera
     *  motion is the history's resampling, not the view (host_sample/testbed/README.md, "What holds
     *  env back at 1024x640").  false = the mirror as the camera sees it. */
    bool frozen_mirror_view = false;
    /** The light's turn at frame `index`, radians (0 when light_speed is 0). */
    float light_angle(int index) const;
    /** Towards the sun at frame `index`: sun_direction turned by light_angle(index). */
    glm::vec3 sun_direction_at(int index) const;
};

}  // namespace rrc_sample
