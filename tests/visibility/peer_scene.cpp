#include "peer_scene.h"

#include <cmath>
#include <limits>

namespace rrc_peer {

namespace {

const double kInf = std::numeric_limits<double>::infinity();

// The world direction of the frame's ray through pixel coordinate (px, py), scaled so its view z is -1:
// the ray parameter is then the planar depth.
glm::dvec3 ray_direction(const rrc_scene::Scene& scene, const rrc_scene::CameraPose& cam, double px, double py) {
    const rrc_scene::Projection& p = scene.projection();
    const double x = (2.0 * px / scene.width() - 1.0) * p.aspect * p.tan_half_fovy;
    const double y = -(2.0 * py / scene.height() - 1.0) * p.tan_half_fovy;  // NDC y points down
    return cam.basis * glm::dvec3(x, y, -1.0);
}

// Planar depth where the ray through (px, py) meets the plane through X with normal N.
double plane_depth(const rrc_scene::Scene& scene, const rrc_scene::CameraPose& cam, double px, double py, const glm::dvec3& X,
                   const glm::dvec3& N) {
    const glm::dvec3 dir = ray_direction(scene, cam, px, py);
    return glm::dot(N, X - cam.eye) / glm::dot(N, dir);
}

}  // namespace

glm::dvec3 object_normal(const rrc_scene::ObjectShape& shape, const glm::dvec3& p) {
    using rrc_scene::Shape;
    if (shape.shape == Shape::Plane) return glm::dvec3(0.0, 1.0, 0.0);
    if (shape.shape == Shape::Sphere) return glm::normalize(p);
    int axis = 0;  // the box face the point lies on: the largest |p_i| / half_i
    double best = -1.0;
    for (int i = 0; i < 3; ++i) {
        const double r = std::fabs(p[i]) / shape.half[i];
        if (r > best) best = r, axis = i;
    }
    glm::dvec3 n(0.0);
    n[axis] = p[axis] < 0.0 ? -1.0 : 1.0;
    return n;
}

rrc_ref::peers::GBuffer make_gbuffer(const rrc_scene::Scene& scene, const rrc_scene::Frame& f) {
    rrc_ref::peers::GBuffer g;
    g.width = f.width;
    g.height = f.height;
    g.tan_half_fovy = scene.projection().tan_half_fovy;
    const size_t n = g.size();
    g.view_z.assign(n, kInf);
    g.device_z.assign(n, kInf);
    g.normal.assign(n, glm::dvec3(0.0));
    g.z_fwidth.assign(n, 0.0);
    g.n_fwidth.assign(n, 0.0);
    g.background.assign(n, 0);
    const rrc_scene::SceneConfig& c = scene.config();
    const rrc_scene::CameraPose cam = scene.camera(f.index);
    for (int j = 0; j < f.height; ++j)
        for (int i = 0; i < f.width; ++i) {
            const size_t k = static_cast<size_t>(j) * f.width + i;
            const double stored = f.depth[k];
            g.device_z[k] = c.depth_mode == RRC_DEPTH_MODE_LINEAR ? stored
                                                                  : rrc_scene::linearize_depth(c.depth_mode, stored, c.near_plane, c.far_plane);
            const int32_t o = f.object_id[k];
            if (o == rrc_scene::OBJECT_BACKGROUND) {
                g.background[k] = 1;
                continue;
            }
            g.view_z[k] = static_cast<float>(f.linear_depth[k]);  // the renderer's fp32 linear-depth guide
            const rrc_scene::RigidTransform m = scene.model(o, f.index);
            const rrc_scene::ObjectShape& shape = scene.shape(o);
            const glm::dvec3 N = m.dir_to_world(object_normal(shape, f.object_pos[k]));
            const glm::dvec3 X = m.to_world(f.object_pos[k]);
            g.normal[k] = N;
            // The pixel's own sample coordinate, and one pixel right and down on its tangent plane.
            const double px = i + 0.5 + f.jitter[0], py = j + 0.5 + f.jitter[1];
            const double d = f.linear_depth[k];
            const double dx = plane_depth(scene, cam, px + 1.0, py, X, N), dy = plane_depth(scene, cam, px, py + 1.0, X, N);
            g.z_fwidth[k] = std::max(std::fabs(dx - d), std::fabs(dy - d));
            if (shape.shape == rrc_scene::Shape::Sphere) {
                // The normal field across the tangent plane (plane and box faces: constant, 0).
                auto normal_at = [&](double qx, double qy, double depth) {
                    const glm::dvec3 P = cam.eye + depth * ray_direction(scene, cam, qx, qy);
                    return m.dir_to_world(glm::normalize(m.to_object(P)));
                };
                const glm::dvec3 ddx = normal_at(px + 1.0, py, dx) - N, ddy = normal_at(px, py + 1.0, dy) - N;
                g.n_fwidth[k] = glm::length(glm::abs(ddx) + glm::abs(ddy));
            }
        }
    return g;
}

rrc_ref::peers::Reprojection make_reprojection(const rrc_scene::Scene& scene, const rrc_scene::Frame& f) {
    rrc_ref::peers::Reprojection r;
    const size_t n = static_cast<size_t>(f.width) * f.height;
    r.qx.assign(n, NAN);
    r.qy.assign(n, NAN);
    r.on_screen.assign(n, 0);
    r.prev_view_z.assign(n, kInf);
    r.view_dir.assign(n, glm::dvec3(0.0));
    r.parallax_px.assign(n, 0.0);
    const rrc_scene::CameraPose cam = scene.camera(f.index), prev_cam = scene.camera(f.prev_index);
    const glm::dmat4 vp = scene.view_proj(f.index);
    auto pixel_of = [&](const glm::dvec3& P) {
        const glm::dvec4 clip = vp * glm::dvec4(P, 1.0);
        return glm::dvec2((clip.x / clip.w + 1.0) * 0.5 * f.width, (clip.y / clip.w + 1.0) * 0.5 * f.height);
    };
    for (int j = 0; j < f.height; ++j)
        for (int i = 0; i < f.width; ++i) {
            const size_t k = static_cast<size_t>(j) * f.width + i;
            const float* pc = &f.prev_clip[4 * k];
            if (pc[3] > 0.0f) {
                const double ux = (double(pc[0]) / pc[3] + 1.0) * 0.5, uy = (double(pc[1]) / pc[3] + 1.0) * 0.5;
                r.qx[k] = ux * f.width - f.prev_jitter[0];
                r.qy[k] = uy * f.height - f.prev_jitter[1];
                r.on_screen[k] = ux >= 0.0 && ux <= 1.0 && uy >= 0.0 && uy <= 1.0;
                r.prev_view_z[k] = pc[3];
            }
            const int32_t o = f.object_id[k];
            if (o == rrc_scene::OBJECT_BACKGROUND) continue;
            const glm::dvec3 X = scene.model(o, f.index).to_world(f.object_pos[k]);
            const glm::dvec3 X_prev = scene.model(o, f.prev_index).to_world(f.object_pos[k]);
            r.view_dir[k] = glm::normalize(cam.eye - X);
            // NRD's ComputeParallaxInPixels(Xprev - gCameraDelta, pixelUv, gWorldToClip): the previous
            // camera-relative position seen from the current camera, against the point itself (0 for
            // a pure rotation).
            r.parallax_px[k] = glm::length(pixel_of(cam.eye + (X_prev - prev_cam.eye)) - pixel_of(X));
        }
    return r;
}

}  // namespace rrc_peer
