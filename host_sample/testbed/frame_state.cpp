#include "frame_state.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <random>

namespace rrc_sample {
namespace {

glm::mat4 camera_view_proj(const Scene& scene, const RenderSettings& s, double t) {
    const Camera c = scene.camera(t);
    const glm::mat4 view = glm::lookAt(c.eye, c.target, glm::vec3(0, 1, 0));
    return reversed_perspective(c.fov_y, (float)s.width / (float)s.height, scene.near_plane, scene.far_plane) * view;
}

glm::mat4 sun_view_proj(const Scene& scene, glm::vec3 towards_sun) {
    const float e = scene.sun_extent;
    const glm::mat4 view = glm::lookAt(towards_sun * 40.0f, glm::vec3(0.0f), glm::vec3(0, 1, 0));
    return glm::orthoRH_ZO(-e, e, -e, e, 1.0f, 80.0f) * view;
}

}  // namespace

glm::mat4 reversed_perspective(float fov_y, float aspect, float n, float f) {
    const float t = std::tan(0.5f * fov_y);
    glm::mat4 p(0.0f);
    p[0][0] = 1.0f / (aspect * t);
    p[1][1] = -1.0f / t;  // Vulkan: y down
    p[2][2] = n / (f - n);
    p[2][3] = -1.0f;
    p[3][2] = n * f / (f - n);  // z_ndc = n (f - d) / (d (f - n)): 1 at the near plane, 0 at the far plane
    return p;
}

glm::mat4 lamp_view_proj(const AreaLight& lamp, glm::vec3 point) {
    const glm::mat4 view = glm::lookAt(point, point + lamp.facing, glm::normalize(lamp.half_v));
    return glm::perspectiveRH_ZO(lamp.fov, 1.0f, lamp.near_plane, lamp.far_plane) * view;
}

glm::vec3 lamp_sequence_point(const AreaLight& lamp, int index, uint32_t seed) {
    double shift_a = 0.0, shift_b = 0.0;
    if (seed != 0) {
        std::mt19937 rng(0x50f7u + seed);
        std::uniform_real_distribution<double> uni(0.0, 1.0);
        shift_a = uni(rng);
        shift_b = uni(rng);
    }
    const double a = std::fmod(0.5 + shift_a + 0.75487766624669276 * (double)index, 1.0);
    const double b = std::fmod(0.5 + shift_b + 0.56984029099805327 * (double)index, 1.0);
    return lamp.centre + (float)(2.0 * a - 1.0) * lamp.half_u + (float)(2.0 * b - 1.0) * lamp.half_v;
}

std::vector<glm::vec3> lamp_frame_points(const AreaLight& lamp, int index, int k, uint32_t seed) {
    std::vector<glm::vec3> points;
    for (int j = 0; j < k; ++j) points.push_back(lamp_sequence_point(lamp, index * k + j, seed));
    return points;
}

glm::vec3 lamp_grid_point(const AreaLight& lamp, int j, int count) {
    int m = 1;
    while (m * m < count) ++m;
    const float u = ((float)(j % m) + 0.5f) / (float)m, v = ((float)(j / m) + 0.5f) / (float)m;
    return lamp.centre + (2.0f * u - 1.0f) * lamp.half_u + (2.0f * v - 1.0f) * lamp.half_v;
}

std::vector<glm::vec2> poisson_disk(int k) {
    std::mt19937 rng(20070804u);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    auto random_in_disk = [&] {
        const float r = std::sqrt(uni(rng)), a = 6.2831853f * uni(rng);
        return glm::vec2(r * std::cos(a), r * std::sin(a));
    };
    std::vector<glm::vec2> pts;
    for (int i = 0; i < k; ++i) {
        glm::vec2 best(0.0f);
        float best_d = -1.0f;
        const int candidates = 20 * (i + 1);
        for (int c = 0; c < candidates; ++c) {
            glm::vec2 p = random_in_disk();
            float d = 1e9f;
            for (const glm::vec2& q : pts) d = std::min(d, glm::length(p - q));
            // Keep away from the rim too, so the pattern is not all on the edge.
            d = std::min(d, 2.0f * (1.0f - glm::length(p)) + 0.25f);
            if (d > best_d) best_d = d, best = p;
        }
        pts.push_back(best);
    }
    return pts;
}

FrameState make_frame_state(const Scene& scene, const RenderSettings& s, int index) {
    FrameState st;
    FrameUniforms& u = st.uniforms;
    const double t = (double)index / s.fps, tp = (double)std::max(index - 1, 0) / s.fps;
    const glm::mat4 vp = camera_view_proj(scene, s, t), pvp = camera_view_proj(scene, s, tp);
    u.view_proj = vp;
    u.prev_view_proj = pvp;
    u.inv_view_proj = glm::inverse(vp);
    st.view_proj = glm::dmat4(vp);
    st.prev_view_proj = glm::dmat4(pvp);
    st.eye = glm::dvec3(scene.camera(t).eye);
    st.prev_eye = glm::dvec3(scene.camera(tp).eye);
    st.lighting_turn = std::abs(scene.light_angle(index) - scene.light_angle(std::max(index - 1, 0)));

    const float sun_texel = 2.0f * scene.sun_extent / (float)s.sun_map;
    // The moving light (Scene::light_speed): the sun and, through bump.z, the environment map turn together.
    const glm::vec3 sun = scene.sun_direction_at(index);
    u.sun_vp = sun_view_proj(scene, sun);
    u.sun_dir = glm::vec4(sun, 1.5f * sun_texel);
    u.sun_colour = glm::vec4(scene.sun_colour, s.pcf_radius);
    u.ambient = glm::vec4(scene.ambient, 0.03f);

    // This frame's point on the area light: the R2 low-discrepancy sequence,
    // so any run of consecutive frames covers the light evenly.
    const AreaLight& L = scene.lamp;
    const glm::vec3 point = lamp_sequence_point(L, index, s.seed);  // = lamp_frame_points(L, index, 1, seed)[0]
    u.lamp_point_vp = lamp_view_proj(L, point);
    u.lamp_centre_vp = lamp_view_proj(L, L.centre);
    u.lamp_centre = glm::vec4(L.centre, L.near_plane);
    u.lamp_u = glm::vec4(L.half_u, L.far_plane);
    u.lamp_v = glm::vec4(L.half_v, std::tan(0.5f * L.fov));
    u.lamp_point = glm::vec4(point, (float)s.lamp_map);
    u.lamp_facing = glm::vec4(L.facing, 0.004f);
    u.lamp_colour = glm::vec4(L.colour, (float)s.sun_map);

    const Camera cam = scene.camera(t);
    u.camera_pos = glm::vec4(cam.eye, (float)t);
    u.sphere = scene.sphere;
    u.bump = glm::vec4(55.0f, 0.45f, scene.light_angle(index), 0.0f);  // z: the environment map's turn (shaders/env.glsl)
    u.mirror_eye = scene.frozen_mirror_view ? glm::vec4(scene.camera(0.0).eye, 1.0f) : glm::vec4(0.0f);
    u.frame = glm::uvec4((uint32_t)index, (uint32_t)s.taps, s.width, s.height);
    const std::vector<glm::vec2> disk = poisson_disk(s.taps);
    for (int i = 0; i < kMaxTaps; ++i) u.poisson[i] = i < (int)disk.size() ? glm::vec4(disk[i], 0, 0) : glm::vec4(0.0f);

    for (size_t i = 0; i < scene.objects.size(); ++i) {
        GpuObject o;
        o.model = scene.model(i, t);
        o.prev_model = scene.model(i, tp);
        const uint32_t m = scene.objects[i].material;
        o.material = glm::uvec4(m, 0, 0, 0);
        switch (m) {
            case kMatGround: o.albedo = glm::vec4(0.55f, 0.52f, 0.45f, 1); break;
            case kMatStone: o.albedo = glm::vec4(0.78f, 0.74f, 0.66f, 1); break;
            case kMatSphere: o.albedo = glm::vec4(0.9f, 0.9f, 0.9f, 1); break;
            default: o.albedo = glm::vec4(0.75f, 0.22f, 0.12f, 1); break;
        }
        st.objects.push_back(o);
    }
    return st;
}

}  // namespace rrc_sample
