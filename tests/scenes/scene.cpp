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

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// Thin-card layout, in units of the wall distance d: the wall reaches far past
// the view (its receding side meets the far plane or the horizon); the card
// spans the centre of the view and the wall beyond it, away from the camera.
constexpr double kWallHalf = 50.0;
constexpr double kCardHalfAlong = 0.5;   // along the slide (the wall's horizontal tangent)
constexpr double kCardHalfAcross = 0.3;  // vertical

// Object space of a plane shape is y = 0 (objects.h): the wall's rotation
// takes object x to the horizontal tangent t1, y to the normal n (facing the
// camera) and z to -y (right-handed: t1 x n = (0, -1, 0)).
glm::dmat3 wall_rotation(double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return glm::dmat3(glm::dvec3(c, 0.0, -s), glm::dvec3(s, 0.0, c), glm::dvec3(0.0, -1.0, 0.0));
}

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
    if (!(c.grazing_max_angle_degrees > 0.0 && c.grazing_max_angle_degrees < 90.0))
        throw std::invalid_argument("rrc_scene: grazing_max_angle_degrees must be in (0, 90)");
    if (!(c.wall_angle_degrees >= 0.0 && c.wall_angle_degrees <= 89.0) || !(c.wall_distance > 0.0) ||
        !(c.card_gap > 0.0 && c.card_gap < 0.5))
        throw std::invalid_argument("rrc_scene: thin card needs wall angle in [0, 89], distance > 0, gap in (0, 0.5)");
    projection_ = make_projection(c.depth_mode, c.near_plane, c.far_plane, c.fovy_degrees, static_cast<double>(c.width) / c.height);
    if (c.layout == SceneLayout::THIN_CARD) {
        const double d = c.wall_distance;
        objects_ = {OBJECT_WALL, OBJECT_CARD};
        shapes_[OBJECT_WALL] = {Shape::Plane, glm::dvec3(kWallHalf * d, 0.0, kWallHalf * d), 0.0};
        shapes_[OBJECT_CARD] = {Shape::Plane, glm::dvec3(kCardHalfAlong * d, 0.0, kCardHalfAcross * d), 0.0};
    } else {
        for (int32_t id = 0; id < OBJECT_COUNT; ++id) {
            objects_.push_back(id);
            shapes_[id] = object_shape(id);
        }
    }
}

CameraPose Scene::camera(int frame) const {
    const SceneConfig& c = config_;
    if (c.layout == SceneLayout::THIN_CARD) return CameraPose{};  // at the origin, looking down -z
    const double t = c.camera_motion ? frame : 0;
    if (c.camera_path == CameraPath::GRAZING)
        return grazing_camera_pose(t, c.camera_speed, c.fovy_degrees, projection_.aspect, c.grazing_max_angle_degrees);
    return camera_pose(t, c.camera_speed);
}

RigidTransform Scene::thin_card_model(int32_t object, int frame) const {
    const SceneConfig& c = config_;
    const double angle = c.wall_angle_degrees * kDegree, d = c.wall_distance;
    RigidTransform x;
    x.rotation = wall_rotation(angle);
    x.translation = glm::dvec3(0.0, 0.0, -d);
    if (object != OBJECT_CARD) return x;
    const glm::dvec3 normal = x.rotation[1], along = x.rotation[0];
    // The central ray (0, 0, -1) meets the plane n.(p - p0) = g at depth
    // d - g / cos(angle): a gap of card_gap * d along that ray needs
    // g = card_gap * d * cos(angle).  The slide: card_speed_px pixels of the
    // wall's centre, i.e. footprint / cos(angle) along the wall.
    const double cos_a = std::cos(angle);
    const double step = c.card_speed_px * pixel_footprint(d) / cos_a;
    // The card's trailing (camera-side) edge crosses the wall's centre at
    // frame 2, so the wall it reveals lies near the view distance d.
    x.translation += normal * (c.card_gap * d * cos_a) + along * (kCardHalfAlong * d + step * (frame - 2));
    return x;
}

glm::dmat4 Scene::view_proj(int frame) const { return projection_.matrix * camera(frame).view_matrix(); }

RigidTransform Scene::model(int32_t object, int frame) const {
    if (config_.layout == SceneLayout::THIN_CARD) return thin_card_model(object, config_.object_motion ? frame : 0);
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

bool Scene::near_other_object(int32_t object, const FrameState& st, const glm::dvec3& world, double distance) const {
    for (int32_t other : objects_) {
        if (other == object) continue;
        if (shape_distance(shapes_[other], st.models[other].to_object(world)) < distance) return true;
    }
    return false;
}

float Scene::stored_depth(double d) const {
    if (config_.depth_mode == RRC_DEPTH_MODE_LINEAR) return static_cast<float>(d);
    return static_cast<float>(quantize_ndc(projection_.ndc_z(d)));
}

float Scene::background_depth() const {
    if (config_.depth_mode == RRC_DEPTH_MODE_LINEAR) return config_.linear_background;
    return config_.depth_mode == RRC_DEPTH_MODE_REVERSED ? 0.0f : 1.0f;
}

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
    for (int32_t id : objects_) st.models[id] = model(id, frame);
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
    for (int32_t id : objects_) {
        const RigidTransform& m = st.models[id];
        const glm::dvec3 o = m.to_object(cam.eye), d = m.dir_to_object(hit.direction);
        const double t = intersect_shape(shapes_[id], o, d, config_.near_plane, best);
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

    const float background = background_depth();
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
                f.depth[k] = background;
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
                f.depth[k] = stored_depth(d);
                const double stored = f.depth[k];
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
