#include "scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <stdexcept>

namespace rrc_sample {
namespace {

glm::mat4 at(glm::vec3 p) { return glm::translate(glm::mat4(1.0f), p); }

AreaLight make_lamp(glm::vec3 centre, glm::vec3 target, float half_size, glm::vec3 colour) {
    AreaLight l;
    l.centre = centre;
    l.facing = glm::normalize(target - centre);
    const glm::vec3 side = glm::normalize(glm::cross(l.facing, glm::vec3(0, 1, 0)));
    l.half_u = side * half_size;
    l.half_v = glm::normalize(glm::cross(side, l.facing)) * half_size;
    l.colour = colour;
    return l;
}

}  // namespace

const char* material_name(uint32_t m) {
    static const char* const names[kMaterialCount] = {"background", "ground", "stone", "sphere", "torus"};
    return m < kMaterialCount ? names[m] : "?";
}

std::vector<std::string> Scene::names() { return {"temple", "courtyard"}; }

Scene Scene::make(const std::string& name) {
    if (name != "temple" && name != "courtyard") throw std::runtime_error("unknown scene \"" + name + "\" (temple, courtyard)");
    Scene s;
    s.name = name;
    // Meshes: 0 ground, 1 stylobate (steps), 2 column, 3 roof slab, 4 sphere, 5 torus.
    s.meshes.push_back(make_plane(40.0f, 4));
    s.meshes.push_back(make_box({6.2f, 0.25f, 3.2f}));
    s.meshes.push_back(make_cylinder(0.32f, 3.6f, 20));
    s.meshes.push_back(make_box({6.4f, 0.3f, 3.4f}));
    s.meshes.push_back(make_sphere(1.0f, 64, 32));  // unit sphere, scaled by the model matrix
    s.meshes.push_back(make_torus(0.75f, 0.25f, 40, 16));

    s.objects.push_back({0, kMatGround, glm::mat4(1.0f), false});
    s.objects.push_back({1, kMatStone, at({0, 0.25f, 0}), false});
    // The small temple: two rows of six columns on the stylobate, a roof slab on top.
    for (int row = 0; row < 2; ++row)
        for (int i = 0; i < 6; ++i) s.objects.push_back({2, kMatStone, at({-5.0f + 2.0f * (float)i, 0.5f, row ? -2.3f : 2.3f}), false});
    s.objects.push_back({3, kMatStone, at({0, 4.4f, 0}), false});
    if (name == "temple") {
        s.sphere = {-3.2f, 1.3f, 5.6f, 1.3f};
        s.objects.push_back({4, kMatSphere, glm::scale(at(glm::vec3(s.sphere)), glm::vec3(s.sphere.w)), false});
        s.signals = kSignalPcf | kSignalEnv | kSignalSoft;
    } else {
        s.sphere = {0, -100.0f, 0, 0.0f};  // none
        s.signals = kSignalPcf | kSignalSoft;
    }
    s.objects.push_back({5, kMatMover, glm::mat4(1.0f), true});

    s.sun_direction = glm::normalize(glm::vec3(0.55f, 0.75f, 0.35f));
    s.sun_colour = glm::vec3(1.6f, 1.5f, 1.3f);
    s.ambient = glm::vec3(0.16f, 0.18f, 0.22f);
    s.lamp = make_lamp({5.5f, 7.5f, 7.0f}, {0.5f, 0.0f, 3.0f}, 1.1f, glm::vec3(60.0f, 52.0f, 42.0f));
    return s;
}

glm::mat4 Scene::model(size_t i, double t) const {
    const SceneObject& o = objects.at(i);
    if (!o.moves) return o.base;
    // The mover: a spinning torus flying to and fro in front of the temple.
    const float x = 4.5f * (float)std::sin(0.6 * t);
    const float y = 1.5f + 0.5f * (float)std::sin(2.1 * t);
    glm::mat4 m = at({x, y, 4.2f});
    m = glm::rotate(m, (float)(1.7 * t), glm::normalize(glm::vec3(1.0f, 0.3f, 0.2f)));
    return m;
}

float Scene::light_angle(int index) const { return glm::radians(light_speed) * (float)index; }

glm::vec3 Scene::sun_direction_at(int index) const {
    if (light_speed == 0.0f) return sun_direction;  // bit for bit the fixed light
    // A right-handed turn about +y (GLM's rotate); shaders/env.glsl turns the environment map the same way.
    return glm::vec3(glm::rotate(glm::mat4(1.0f), light_angle(index), glm::vec3(0, 1, 0)) * glm::vec4(sun_direction, 0.0f));
}

Camera Scene::camera(double t) const {
    // A slow arc in front of the temple, rising a little, looking at its steps.
    const double a = 1.95 - 0.35 * t * camera_speed;  // radians around the y axis
    const float r = 15.0f;
    Camera c;
    c.eye = glm::vec3(r * (float)std::cos(a), 4.2f + 0.4f * (float)(t * camera_speed), r * (float)std::sin(a));
    c.target = glm::vec3(0.0f, 1.6f, 1.5f);
    c.fov_y = 0.87f;
    return c;
}

}  // namespace rrc_sample
