#include "scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace rrc_bench {
namespace {

// A reversed-z (near 1, far 0) perspective for Vulkan clip space (y down).
glm::dmat4 projection(double aspect) {
    glm::dmat4 p = glm::perspectiveRH_ZO(glm::radians(60.0), aspect, (double)kNear, (double)kFar);
    p[1][1] = -p[1][1];
    glm::dmat4 reverse(1.0);
    reverse[2][2] = -1.0;  // z' = w - z
    reverse[3][2] = 1.0;
    return reverse * p;
}

// 6 cm sideways between the poses: a few pixels of motion at 1080p.
glm::dvec3 eye_of(int pose) { return glm::dvec3(-0.03 + 0.06 * pose, 1.6, 5.0); }

glm::dmat4 view_proj(int pose, double aspect) {
    return projection(aspect) * glm::lookAtRH(eye_of(pose), glm::dvec3(0.0, 0.2, 0.0), glm::dvec3(0.0, 1.0, 0.0));
}

struct Sphere {
    glm::dvec3 centre;
    double radius;
    uint32_t id;
};
const Sphere kSpheres[] = {{{0.0, 1.0, 0.0}, 1.0, 2}, {{1.8, 0.6, -1.0}, 0.6, 3}};
constexpr double kPlaneHalfExtent = 30.0;  // beyond it: sky (background)

// Nearest hit of the ray o + t d (t > 0): its distance and object id, id 0 = sky.
uint32_t trace(const glm::dvec3& o, const glm::dvec3& d, double& t_hit) {
    uint32_t id = 0;
    t_hit = 1e30;
    if (d.y < 0.0) {
        const double t = -o.y / d.y;
        const glm::dvec3 p = o + t * d;
        if (std::abs(p.x) < kPlaneHalfExtent && std::abs(p.z) < kPlaneHalfExtent) {
            t_hit = t;
            id = 1;
        }
    }
    for (const Sphere& s : kSpheres) {
        const glm::dvec3 oc = o - s.centre;
        const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - s.radius * s.radius, disc = b * b - c;
        if (disc < 0.0) continue;
        const double t = -b - std::sqrt(disc);
        if (t > 0.0 && t < t_hit) {
            t_hit = t;
            id = s.id;
        }
    }
    return id;
}

// A 32-bit integer hash (Wellons' lowbias32): deterministic noise without state.
uint32_t hash(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
float unit(uint32_t a, uint32_t b) { return (float)(hash(a * 0x9E3779B9u ^ hash(b)) >> 8) * (1.0f / 16777216.0f); }

void render_pose(const Config& cfg, int pose, PoseFrame& f) {
    const uint32_t W = cfg.width, H = cfg.height;
    const double aspect = (double)W / (double)H;
    f.view_proj = view_proj(pose, aspect);
    f.prev_view_proj = view_proj(1 - pose, aspect);
    f.eye = eye_of(pose), f.prev_eye = eye_of(1 - pose);
    const glm::dmat4 inv = glm::inverse(f.view_proj);
    const uint32_t n = floats_per_pixel(cfg.source);
    f.depth.assign((size_t)W * H, 0.0f);
    f.reprojection.assign((size_t)W * H * n, 0.0f);
    if (cfg.object_id) f.object_id.assign((size_t)W * H, 0u);
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            const size_t i = (size_t)y * W + x;
            const double u = (x + 0.5) / W, v = (y + 0.5) / H;
            const glm::dvec4 a = inv * glm::dvec4(2.0 * u - 1.0, 2.0 * v - 1.0, 1.0, 1.0);  // near plane
            const glm::dvec4 b = inv * glm::dvec4(2.0 * u - 1.0, 2.0 * v - 1.0, 0.5, 1.0);
            const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
            double t;
            const uint32_t id = trace(o, d, t);
            if (cfg.object_id) f.object_id[i] = id;
            float* r = n ? &f.reprojection[i * n] : nullptr;
            if (id == 0) {  // sky: depth 0, no motion
                if (n == 4) r[3] = 1.0f;
                continue;
            }
            const glm::dvec4 p(o + t * d, 1.0);
            const glm::dvec4 cur = f.view_proj * p, prev = f.prev_view_proj * p;
            f.depth[i] = (float)(cur.z / cur.w);
            const double pu = prev.x / prev.w * 0.5 + 0.5, pv = prev.y / prev.w * 0.5 + 0.5;
            if (n == 4)
                for (int k = 0; k < 4; ++k) r[k] = (float)prev[k];
            if (n == 2 || n == 3) {
                r[0] = (float)(pu - u);
                r[1] = (float)(pv - v);
            }
            if (n == 3) r[2] = (float)(prev.z / prev.w - cur.z / cur.w);
        }
}

}  // namespace

uint32_t floats_per_pixel(rrc_reprojection source) {
    switch (source) {
        case RRC_REPROJECTION_PREV_CLIP: return 4;
        case RRC_REPROJECTION_MOTION: return 2;
        case RRC_REPROJECTION_MOTION_DEPTH: return 3;
        default: return 0;
    }
}

SceneInputs make_scene(const Config& cfg) {
    SceneInputs s;
    s.width = cfg.width;
    s.height = cfg.height;
    render_pose(cfg, 0, s.poses[0]);
    render_pose(cfg, 1, s.poses[1]);
    const size_t px = (size_t)cfg.width * cfg.height;
    for (size_t c = 0; c < cfg.channels.size(); ++c) {
        const uint32_t comps = cfg.channels[c].components;
        std::vector<float> v(px * comps);
        for (size_t i = 0; i < v.size(); ++i) v[i] = unit((uint32_t)i, (uint32_t)c * 2 + 1);
        s.samples.push_back(std::move(v));
        std::vector<float> w;
        if (cfg.channels[c].confidence) {
            w.resize(px);
            for (size_t i = 0; i < px; ++i) w[i] = unit((uint32_t)i, (uint32_t)c * 2 + 2);
        }
        s.confidence.push_back(std::move(w));
        std::vector<float> b;
        if (cfg.channels[c].residual) {
            b.resize(px * comps);
            for (size_t i = 0; i < b.size(); ++i) b[i] = unit((uint32_t)i, (uint32_t)c * 2 + 101);
        }
        s.base.push_back(std::move(b));
    }
    if (cfg.nocache) {
        s.nocache.resize(px);
        for (size_t i = 0; i < px; ++i) s.nocache[i] = unit((uint32_t)i, 99u) < cfg.nocache_share ? 1 : 0;
    }
    return s;
}

}  // namespace rrc_bench
