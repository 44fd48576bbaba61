#include "reproject.h"

#include "rrc_kernel_interface.h"  // RRC_ADAPTIVE_CAMERA_ULPS

#include <cmath>

#include <glm/gtc/type_ptr.hpp>

namespace rrc_ref {

namespace {

int data_components(rrc_reprojection source) {
    switch (source) {
        case RRC_REPROJECTION_PREV_CLIP: return 4;
        case RRC_REPROJECTION_MOTION: return 2;
        case RRC_REPROJECTION_MOTION_DEPTH: return 3;
        default: return 0;  // CAMERA
    }
}

struct Clip {
    Bounded x, y, z, w;
};

// Previous clip position -> uv_prev, e, w (PREV_CLIP, and CAMERA after M).
Reprojected from_clip(const Params& p, const Clip& c) {
    Bounded one = exact(1.0), half = exact(0.5);
    Reprojected r;
    r.uv_x = (c.x / c.w + one) * half;
    r.uv_y = (c.y / c.w + one) * half;
    r.e = p.mode == RRC_DEPTH_MODE_LINEAR ? c.w : c.z / c.w;
    r.w = c.w;
    return r;
}

// M (double, applied in fp32: each entry rounded once) times v.
Clip transform(const glm::dmat4& m, const Bounded v[4]) {
    Bounded out[4];
    for (int row = 0; row < 4; ++row) {
        Bounded acc = as_f32(m[0][row]) * v[0];
        for (int col = 1; col < 4; ++col) acc = acc + as_f32(m[col][row]) * v[col];
        out[row] = acc;
    }
    return {out[0], out[1], out[2], out[3]};
}

}  // namespace

Camera make_camera(const rrc_frame_desc& frame) {
    glm::dmat4 vp = glm::make_mat4(frame.view_proj);  // column-major, as GLM stores it
    glm::dmat4 vp_prev = glm::make_mat4(frame.prev_view_proj);
    glm::dmat4 inv = glm::inverse(vp);
    Camera cam;
    cam.m = vp_prev * inv;
    cam.r = glm::dvec4(inv[0][3], inv[1][3], inv[2][3], inv[3][3]);  // row 3
    return cam;
}

bool reprojection_data_finite(const Params& p, const rrc_frame_desc& frame, size_t pixel) {
    int n = data_components(p.source);
    for (int k = 0; k < n; ++k)
        if (!std::isfinite(frame.reprojection[pixel * n + k])) return false;
    return true;
}

Reprojected reproject(const Params& p, const rrc_frame_desc& frame, const Camera& cam, int i, int j, double d) {
    // The true sample position: the pixel centre plus this frame's jitter.
    Bounded uv_x = (exact(i + 0.5) + exact(frame.jitter[0])) / exact(p.width);
    Bounded uv_y = (exact(j + 0.5) + exact(frame.jitter[1])) / exact(p.height);
    size_t pixel = static_cast<size_t>(j) * p.width + i;
    int n = data_components(p.source);
    const float* data = n ? frame.reprojection + pixel * n : nullptr;

    if (p.source == RRC_REPROJECTION_PREV_CLIP) return from_clip(p, {exact(data[0]), exact(data[1]), exact(data[2]), exact(data[3])});

    if (p.source == RRC_REPROJECTION_MOTION || p.source == RRC_REPROJECTION_MOTION_DEPTH) {
        Reprojected r;
        r.uv_x = uv_x + exact(data[0]) * exact(p.motion_scale[0]);
        r.uv_y = uv_y + exact(data[1]) * exact(p.motion_scale[1]);
        r.w = exact(1.0);
        if (p.source == RRC_REPROJECTION_MOTION_DEPTH)
            r.e = exact(d) + exact(data[2]);
        else  // no depth change known: the current (linear) depth
            r.e = p.linearise() ? linearise(p, exact(d)) : exact(d);
        return r;
    }

    // CAMERA: ndc = 2 uv_s - 1.
    Bounded one = exact(1.0), two = exact(2.0);
    Bounded nx = uv_x * two - one, ny = uv_y * two - one;
    if (p.mode != RRC_DEPTH_MODE_LINEAR) {
        Bounded v[4] = {nx, ny, exact(d), one};
        Reprojected r = from_clip(p, transform(cam.m, v));
        double terms = 0.0;
        for (int k = 0; k < 4; ++k) terms += std::fabs((double)(float)cam.m[k][2] * v[k].v);
        r.camera_err = RRC_ADAPTIVE_CAMERA_ULPS * 0x1p-24 * terms / std::fabs(r.w.v);
        return r;
    }
    // LINEAR: the point of the pixel's ray whose clip w is d.  Its world
    // position has w = r . c_cur = 1, which fixes the clip z.
    Bounded a = as_f32(cam.r.x) * nx + as_f32(cam.r.y) * ny + as_f32(cam.r.w);
    Bounded b = as_f32(cam.r.z);
    Bounded dd = exact(d);
    Bounded v[4] = {nx * dd, ny * dd, (one - dd * a) / b, dd};
    return from_clip(p, transform(cam.m, v));
}

}  // namespace rrc_ref
