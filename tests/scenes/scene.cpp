// Per-pixel ray casting and the per-frame inputs of the analytic scene.
#include "scenes/scene.h"

#include <cstring>
#include <limits>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

#include "scenes/random.h"
#include "scenes/shading.h"

namespace rrc_scene {
namespace {

// Hash streams: each random decision of a pixel draws from its own stream.
enum Stream : uint64_t {
    STREAM_NOISE1 = 1,     // signal1 noise
    STREAM_NOISE4 = 2,     // signal4 noise: 2..5, one per component
    STREAM_INVALID1 = 10,  // is signal1 invalid
    STREAM_INVALID1_KIND = 11,
    STREAM_INVALID4 = 12,  // is signal4 invalid
    STREAM_INVALID4_KIND = 13,
    STREAM_INVALID4_COMP = 14,
};

float invalid_value(uint64_t h) {
    switch (h % 3) {
        case 0: return std::numeric_limits<float>::quiet_NaN();
        case 1: return std::numeric_limits<float>::infinity();
        default: return -std::numeric_limits<float>::infinity();
    }
}

void store_matrix(const glm::dmat4& m, double out[16]) { std::memcpy(out, glm::value_ptr(m), 16 * sizeof(double)); }

}  // namespace

double linearize_depth(uint32_t mode, double z, double n, double f) {
    if (mode == RRC_DEPTH_MODE_REVERSED) return std::isinf(f) ? n / z : n * f / (n + z * (f - n));
    if (mode == RRC_DEPTH_MODE_STANDARD) return std::isinf(f) ? n / (1.0 - z) : n * f / (f - z * (f - n));
    return z;  // LINEAR already is
}

Scene::Scene(const SceneConfig& c) : config_(c) {
    if (c.width <= 0 || c.height <= 0) throw std::invalid_argument("rrc_scene: width and height must be > 0");
    if (c.depth_mode > RRC_DEPTH_MODE_LINEAR) throw std::invalid_argument("rrc_scene: bad depth_mode");
    if (c.depth_format > RRC_DEPTH_FORMAT_UNORM24) throw std::invalid_argument("rrc_scene: bad depth_format");
    if (!(c.near_plane > 0.0) || !(c.far_plane > c.near_plane))
        throw std::invalid_argument("rrc_scene: need 0 < near < far (far may be +inf)");
    if (!(c.fovy_degrees > 0.0 && c.fovy_degrees < 180.0)) throw std::invalid_argument("rrc_scene: bad fovy");
    if (!(c.invalid_fraction >= 0.0 && c.invalid_fraction <= 1.0))
        throw std::invalid_argument("rrc_scene: invalid_fraction must be in [0, 1]");
    projection_ = make_projection(c.depth_mode, c.near_plane, c.far_plane, c.fovy_degrees, static_cast<double>(c.width) / c.height);
}

CameraPose Scene::camera(int frame) const { return camera_pose(config_.camera_motion ? frame : 0, config_.camera_speed); }

glm::dmat4 Scene::view_proj(int frame) const { return projection_.matrix * camera(frame).view_matrix(); }

RigidTransform Scene::model(int32_t object, int frame) const {
    return object_transform(object, config_.object_motion ? frame : 0, config_.object_speed);
}

glm::dvec2 Scene::jitter(int frame) const {
    if (!config_.jitter) return glm::dvec2(0.0);
    // Period 16 (as FSR2 uses short phase counts); index 0 of Halton is 0 and
    // is skipped so the pattern is the familiar (1/2, 1/3), (1/4, 2/3), ...
    const uint32_t index = 1u + static_cast<uint32_t>(((frame % 16) + 16) % 16);
    return glm::dvec2(halton(index, 2) - 0.5, halton(index, 3) - 0.5);
}

double Scene::pixel_footprint(double d) const { return 2.0 * d * projection_.tan_half_fovy / config_.height; }

double Scene::quantize_ndc(double z) const {
    switch (config_.depth_format) {
        case RRC_DEPTH_FORMAT_UNORM16: return std::nearbyint(z * 65535.0) / 65535.0;
        case RRC_DEPTH_FORMAT_UNORM24: return std::nearbyint(z * 16777215.0) / 16777215.0;
        default: return z;
    }
}

FrameState Scene::frame_state(int frame) const {
    FrameState st;
    st.frame = frame;
    st.camera = camera(frame);
    for (int32_t id = 0; id < OBJECT_COUNT; ++id) st.models[id] = model(id, frame);
    return st;
}

Hit Scene::cast(const FrameState& st, double px, double py) const {
    const CameraPose& cam = st.camera;
    const double ndc_x = 2.0 * px / config_.width - 1.0;
    const double ndc_y = 2.0 * py / config_.height - 1.0;
    // View-space direction with z = -1, so the ray parameter is the planar depth.
    const glm::dvec3 dir_view(ndc_x * projection_.aspect * projection_.tan_half_fovy, -ndc_y * projection_.tan_half_fovy, -1.0);
    Hit hit;
    hit.direction = cam.basis * dir_view;
    double best = config_.far_plane;  // hits must satisfy near <= d < far
    for (int32_t id = 0; id < OBJECT_COUNT; ++id) {
        const RigidTransform& m = st.models[id];
        const glm::dvec3 o = m.to_object(cam.eye), d = m.dir_to_object(hit.direction);
        const double t = intersect_object(id, o, d, config_.near_plane, best);
        if (t >= 0.0) {
            best = t;
            hit.object_id = id;
            hit.object = o + t * d;  // in object space directly: no round trip through world
        }
    }
    if (hit.object_id != OBJECT_BACKGROUND) {
        hit.depth = best;
        hit.world = cam.eye + best * hit.direction;
    }
    return hit;
}

std::vector<int32_t> Scene::object_ids(int frame) const {
    const int w = config_.width, h = config_.height;
    const glm::dvec2 jit = jitter(frame);
    const FrameState st = frame_state(frame);
    std::vector<int32_t> ids(static_cast<size_t>(w) * h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) ids[static_cast<size_t>(j) * w + i] = cast(st, i + 0.5 + jit.x, j + 0.5 + jit.y).object_id;
    return ids;
}

Frame Scene::render(int frame, int prev_frame) const {
    const SceneConfig& c = config_;
    const int w = c.width, h = c.height;
    const size_t n = static_cast<size_t>(w) * h;
    const bool linear = c.depth_mode == RRC_DEPTH_MODE_LINEAR;

    Frame f;
    f.index = frame;
    f.prev_index = prev_frame;
    f.width = w;
    f.height = h;
    f.depth_mode = c.depth_mode;
    f.depth.resize(n);
    f.prev_clip.resize(4 * n);
    f.motion.resize(3 * n);
    f.object_id.resize(n);
    f.object_pos.resize(n);
    f.linear_depth.resize(n);
    f.truth1.resize(n);
    f.truth4.resize(4 * n);
    f.signal1.resize(n);
    f.signal4.resize(4 * n);

    const glm::dmat4 vp = view_proj(frame), vp_prev = view_proj(prev_frame);
    store_matrix(vp, f.view_proj);
    store_matrix(vp_prev, f.prev_view_proj);
    const glm::dvec2 jit = jitter(frame), jit_prev = jitter(prev_frame);
    f.jitter[0] = static_cast<float>(jit.x);
    f.jitter[1] = static_cast<float>(jit.y);
    f.prev_jitter[0] = static_cast<float>(jit_prev.x);
    f.prev_jitter[1] = static_cast<float>(jit_prev.y);

    const FrameState st = frame_state(frame), prev_st = frame_state(prev_frame);

    const float background_depth = linear ? c.linear_background : (c.depth_mode == RRC_DEPTH_MODE_REVERSED ? 0.0f : 1.0f);
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            const size_t k = static_cast<size_t>(j) * w + i;
            const double px = i + 0.5 + jit.x, py = j + 0.5 + jit.y;
            const glm::dvec2 uv_s(px / w, py / h);
            const Hit hit = cast(st, px, py);
            f.object_id[k] = hit.object_id;

            glm::dvec4 clip_prev;
            double truth1;
            glm::dvec4 truth4;
            if (hit.object_id == OBJECT_BACKGROUND) {
                f.depth[k] = background_depth;
                f.object_pos[k] = glm::dvec3(0.0);
                f.linear_depth[k] = INFINITY;
                // The sky is at infinity: a direction (w = 0) only sees the rotation.
                clip_prev = vp_prev * glm::dvec4(hit.direction, 0.0);
                glm::dvec2 mv(0.0);
                if (clip_prev.w > 0.0) mv = (glm::dvec2(clip_prev) / clip_prev.w + 1.0) * 0.5 - uv_s;
                f.motion[3 * k + 0] = static_cast<float>(mv.x);
                f.motion[3 * k + 1] = static_cast<float>(mv.y);
                f.motion[3 * k + 2] = 0.0f;
                truth1 = kSky1;
                truth4 = sky4();
            } else {
                f.object_pos[k] = hit.object;
                // The point's clip w is its planar depth: use the ray parameter (exact).
                const double d = hit.depth;
                f.linear_depth[k] = d;
                double stored;
                if (linear) {
                    f.depth[k] = static_cast<float>(d);
                } else {
                    f.depth[k] = static_cast<float>(quantize_ndc(projection_.ndc_z(d)));
                }
                stored = f.depth[k];
                // Move P with its object to the previous frame and project it there.
                const glm::dvec3 p_prev = prev_st.models[hit.object_id].to_world(hit.object);
                clip_prev = vp_prev * glm::dvec4(p_prev, 1.0);
                glm::dvec2 mv(0.0);
                if (clip_prev.w != 0.0) mv = (glm::dvec2(clip_prev) / clip_prev.w + 1.0) * 0.5 - uv_s;
                const double expected = linear ? clip_prev.w : clip_prev.z / clip_prev.w;
                f.motion[3 * k + 0] = static_cast<float>(mv.x);
                f.motion[3 * k + 1] = static_cast<float>(mv.y);
                f.motion[3 * k + 2] = static_cast<float>(expected - stored);
                truth1 = shade1(hit.object_id, hit.object);
                truth4 = shade4(hit.object_id, hit.object);
            }
            for (int q = 0; q < 4; ++q) f.prev_clip[4 * k + q] = static_cast<float>(clip_prev[q]);

            // Signals: truth plus per-component noise (none on the sky).
            const bool noisy = hit.object_id != OBJECT_BACKGROUND;
            const double a = noisy ? c.noise_amplitude : 0.0;
            f.truth1[k] = static_cast<float>(truth1);
            f.signal1[k] = static_cast<float>(truth1 + a * (2.0 * uniform01(hash4(c.seed, frame, k, STREAM_NOISE1)) - 1.0));
            for (int q = 0; q < 4; ++q) {
                f.truth4[4 * k + q] = static_cast<float>(truth4[q]);
                f.signal4[4 * k + q] =
                    static_cast<float>(truth4[q] + a * (2.0 * uniform01(hash4(c.seed, frame, k, STREAM_NOISE4 + q)) - 1.0));
            }
            if (c.invalid_fraction > 0.0) {
                if (uniform01(hash4(c.seed, frame, k, STREAM_INVALID1)) < c.invalid_fraction)
                    f.signal1[k] = invalid_value(hash4(c.seed, frame, k, STREAM_INVALID1_KIND));
                if (uniform01(hash4(c.seed, frame, k, STREAM_INVALID4)) < c.invalid_fraction) {
                    const uint64_t comp = hash4(c.seed, frame, k, STREAM_INVALID4_COMP) % 4;
                    f.signal4[4 * k + comp] = invalid_value(hash4(c.seed, frame, k, STREAM_INVALID4_KIND));
                }
            }
        }
    }
    return f;
}

}  // namespace rrc_scene
