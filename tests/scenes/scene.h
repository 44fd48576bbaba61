// Analytic test scenes rendered on the CPU in double precision.
//
// A ground plane, three axis-aligned boxes, a sphere resting on the ground and
// a floating sphere that moves (its own rigid model matrix per frame), seen by
// a camera that moves along a path.  Every pixel is ray-cast exactly; all
// math is double and values are rounded to float only when written to the
// output arrays.  The per-frame inputs follow docs/CONVENTIONS.md exactly:
//
//  - row 0 at the top; pixel (i, j) centre at uv = ((i+0.5)/W, (j+0.5)/H);
//    uv = (ndc.xy + 1)/2 with NDC y down; NDC z in [0, 1].
//  - jitter: the frame's sample of pixel (i, j) is the ray through the pixel
//    coordinate (i + 0.5 + jx, j + 0.5 + jy), i.e. uv_s of CONVENTIONS.md.
//    Everything of a pixel (depth, prev_clip, motion, ids, signals) describes
//    the surface point P hit by that ray.
//  - matrices and prev_clip/motion are UNJITTERED (projections of P with the
//    unjittered view-projections), as FSR2/NRD expect.
//  - camera and projection conventions: see camera.h.  World: y up, ground y = 0.
//
// Typical use:
//   rrc_scene::SceneConfig cfg; cfg.depth_mode = RRC_DEPTH_MODE_REVERSED;
//   rrc_scene::Scene scene(cfg);
//   for (int t = 0; t < 30; ++t) { rrc_scene::Frame f = scene.render(t); ... }
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "rrc/rrc.h"
#include "scenes/camera.h"
#include "scenes/objects.h"

namespace rrc_scene {

// Which camera path a scene follows (SceneConfig::camera_path).
enum class CameraPath {
    ORBIT,    // camera_pose: orbits the objects from above (the default)
    GRAZING,  // grazing_camera_pose: low, the ground up to grazing_max_angle_degrees from its normal
};

// Which objects a scene holds (SceneConfig::layout).
enum class SceneLayout {
    OBJECTS,  // ground, boxes and spheres (objects.h, ids 0 .. OBJECT_COUNT - 1; the default)
    // A wall (OBJECT_WALL) and a thin card (OBJECT_CARD) in front of it, seen
    // by a fixed camera at the origin looking down -z at the wall's centre
    // (0, 0, -wall_distance), the wall's normal wall_angle_degrees from the
    // view axis (turned about y).  The card is parallel to the wall, card_gap *
    // wall_distance in front of it along the central ray, and slides along the
    // wall away from the camera by card_speed_px pixels a frame (at the
    // wall's centre), so wall pixels it covered are revealed every frame; its
    // trailing edge crosses the wall's centre at frame 2 (the revealed wall
    // lies near depth wall_distance).
    // camera_path, camera_motion, object_speed are ignored.
    THIN_CARD,
};

struct SceneConfig {
    int width = 96;
    int height = 64;
    uint32_t depth_mode = RRC_DEPTH_MODE_STANDARD;  // RRC_DEPTH_MODE_*
    double near_plane = 0.1;
    double far_plane = 100.0;  // +inf allowed (STANDARD, REVERSED, LINEAR)
    // NDC modes: FLOAT32 = fp32 only; UNORM16 / UNORM24 round NDC z to the
    // format's grid k/(2^bits - 1) before the fp32 store.  Ignored for LINEAR.
    uint32_t depth_format = RRC_DEPTH_FORMAT_FLOAT32;
    float linear_background = INFINITY;  // LINEAR background depth (+inf, or e.g. 1e10f as Blender)
    double fovy_degrees = 60.0;          // vertical field of view; pixels are square
    bool jitter = false;                 // Halton(2,3) sub-pixel jitter, see Scene::jitter
    bool camera_motion = true;           // false: the camera stays at its frame-0 pose
    bool object_motion = true;           // false: the moving sphere stays at its frame-0 pose
    double camera_speed = 1.0;           // multiplies the camera path's time
    double object_speed = 1.0;           // multiplies the moving sphere's time
    double noise_amplitude = 0.2;        // signal = truth + U(-a, a), per component, zero mean
    double invalid_fraction = 0.0;       // fraction of samples (per signal) replaced by NaN/+Inf/-Inf
    uint64_t seed = 1;                   // noise and invalid-sample hash seed
    // Appended members (tests/support/scene_frames.h builds configs by member order).
    CameraPath camera_path = CameraPath::ORBIT;
    double grazing_max_angle_degrees = 85.0;  // GRAZING: the largest angle of the ground from its normal
    SceneLayout layout = SceneLayout::OBJECTS;
    double wall_angle_degrees = 0.0;  // THIN_CARD: the wall's normal from the view axis, in [0, 89]
    double wall_distance = 10.0;      // THIN_CARD: d, the wall centre's view distance
    double card_gap = 1e-3;           // THIN_CARD: card to wall along the central ray, in units of d
    double card_speed_px = 2.0;       // THIN_CARD: the card's slide per frame, pixels at the wall's centre
};

// The first surface a ray meets.
struct Hit {
    int32_t object_id = OBJECT_BACKGROUND;
    double depth = INFINITY;    // planar view depth d (= clip w); the ray parameter
    glm::dvec3 world{0.0};      // hit point, world space
    glm::dvec3 object{0.0};     // hit point, the object's own space
    glm::dvec3 direction{0.0};  // world-space ray direction, scaled so its view z is -1
};

// One rendered frame.  Arrays are row-major, row 0 at the top, interleaved.
struct Frame {
    int index = 0;        // this frame's time
    int prev_index = -1;  // the frame prev_clip/motion/prev_* refer to
    int width = 0, height = 0;
    uint32_t depth_mode = RRC_DEPTH_MODE_STANDARD;

    // Depth in the depth mode: STANDARD/REVERSED NDC z (quantised if asked),
    // background 1 / 0; LINEAR planar depth d, background linear_background.
    std::vector<float> depth;
    // Previous clip position (x, y, z, w) of P: previous model matrix,
    // previous UNJITTERED view-projection.  In LINEAR mode z is STANDARD's
    // clip z (w is what the test uses).  Background: VP_prev * (dir, 0), the
    // projection of the sky direction (finite; w <= 0 when behind the camera).
    std::vector<float> prev_clip;
    // (uv_prev - uv_s, expected previous depth - depth): xy from the
    // unjittered projections of P; z in the mode's units (NDC z, or d for
    // LINEAR), taken against the depth value as STORED in `depth` (after
    // quantisation and fp32 rounding) so depth + motion.z reproduces the
    // expected previous depth as closely as fp32 allows.  Background: xy the
    // sky direction's motion (0 if it is behind the previous camera), z = 0.
    std::vector<float> motion;
    double view_proj[16] = {};       // current, unjittered, column-major (GLM), Vulkan clip
    double prev_view_proj[16] = {};  // previous, unjittered
    float jitter[2] = {};            // this frame's sample offset from the pixel centre, pixels, x right y down
    float prev_jitter[2] = {};       // the previous frame's

    // Exact visibility (double, not rounded).
    std::vector<int32_t> object_id;      // -1 = background
    std::vector<glm::dvec3> object_pos;  // hit point in object space (0 for background)
    std::vector<double> linear_depth;    // planar depth d of P, +inf for background

    // Signals.  truth*: noise-free shading of P (shading.h), sky values on the
    // background.  signal*: truth + independent zero-mean uniform noise per
    // component (background: the sky value, no noise), then a fraction
    // `invalid_fraction` of pixels (background included) gets one component
    // replaced by NaN, +Inf or -Inf (independently for signal1 and signal4).
    std::vector<float> truth1, truth4, signal1, signal4;
};

// Everything about one frame's geometry that does not depend on the pixel:
// computed once per frame so casting a ray costs only the intersections.
struct FrameState {
    int frame = 0;
    CameraPose camera;
    RigidTransform models[OBJECT_ID_COUNT];  // those of the scene's objects() are set
};

class Scene {
public:
    // Throws std::invalid_argument on a bad configuration.
    explicit Scene(const SceneConfig& config);

    const SceneConfig& config() const { return config_; }
    const Projection& projection() const { return projection_; }
    int width() const { return config_.width; }
    int height() const { return config_.height; }

    // The ids of the layout's objects, and their shapes.
    const std::vector<int32_t>& objects() const { return objects_; }
    const ObjectShape& shape(int32_t object) const { return shapes_[object]; }

    CameraPose camera(int frame) const;
    glm::dmat4 view_proj(int frame) const;                  // unjittered, column-major
    RigidTransform model(int32_t object, int frame) const;  // object -> world
    // Jitter in pixels, x right y down, in [-0.5, 0.5)^2 (zero if disabled):
    // Halton bases 2 and 3 at index 1 + (frame mod 16), minus 0.5.
    glm::dvec2 jitter(int frame) const;

    // First surface along the frame's ray through the continuous pixel
    // coordinate (px, py) (pixel centres at i + 0.5; uv = (px/W, py/H)).
    // Only hits with near <= d < far count (clipping).
    Hit cast(int frame, double px, double py) const { return cast(frame_state(frame), px, py); }
    Hit cast(const FrameState& state, double px, double py) const;
    FrameState frame_state(int frame) const;

    // World size of one pixel at planar depth d (square pixels).
    double pixel_footprint(double d) const;

    // Does a world point lie within `distance` of the surface of any object
    // but `object`, placed as in `state`?  (The contact rule of false_hits.h
    // and visibility.h.)
    bool near_other_object(int32_t object, const FrameState& state, const glm::dvec3& world, double distance) const;

    // The value `depth` holds for a surface at planar depth d (finite):
    // LINEAR d, else NDC z rounded to the format's grid; both as fp32.  And
    // the value a background pixel holds.
    float stored_depth(double d) const;
    float background_depth() const;

    // Object ids of the frame's (jittered) samples only: cheaper than render().
    std::vector<int32_t> object_ids(int frame) const;

    // Renders `frame` with `prev_frame` as the previous frame (default frame - 1;
    // any other previous frame may be chosen, as when hosts skip frames).
    Frame render(int frame) const { return render(frame, frame - 1); }
    Frame render(int frame, int prev_frame) const;

    // NDC z of planar depth d rounded to the configured format's grid
    // (no rounding for FLOAT32); the value written to `depth` is its fp32 cast.
    double quantize_ndc(double z) const;

private:
    RigidTransform thin_card_model(int32_t object, int frame) const;

    SceneConfig config_;
    Projection projection_;
    std::vector<int32_t> objects_;
    ObjectShape shapes_[OBJECT_ID_COUNT] = {};
};

// Linear (planar) depth from NDC z as in docs/CONVENTIONS.md:
// STANDARD d = n f/(f - z(f - n)); REVERSED d = n f/(n + z(f - n)), n/z if f = +inf.
double linearize_depth(uint32_t depth_mode, double z, double near_plane, double far_plane);

}  // namespace rrc_scene
