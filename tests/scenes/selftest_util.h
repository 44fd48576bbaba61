// Helpers shared by the scene self-tests (not part of the rrc_scenes library).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/bilinear.h"
#include "scenes/scene.h"

namespace rrc_scene_test {

struct ModeCase {
    const char* name;
    uint32_t mode;
    double far_plane;
};

// Every depth mode the scenes support, REVERSED twice (finite and infinite far).
inline std::vector<ModeCase> all_modes() {
    return {{"standard", RRC_DEPTH_MODE_STANDARD, 100.0},
            {"reversed", RRC_DEPTH_MODE_REVERSED, 100.0},
            {"reversed_inf", RRC_DEPTH_MODE_REVERSED, INFINITY},
            {"linear", RRC_DEPTH_MODE_LINEAR, 100.0}};
}

// The default scene with nothing moving (its previous frame is itself).
inline rrc_scene::SceneConfig static_config(bool jitter) {
    rrc_scene::SceneConfig c;
    c.camera_motion = false;
    c.object_motion = false;
    c.jitter = jitter;
    return c;
}

// A fixed camera and the moving sphere six times as fast: a disoccluded band
// about 3 pixels wide behind it every frame.
inline rrc_scene::SceneConfig disocclusion_config() {
    rrc_scene::SceneConfig c;
    c.camera_motion = false;
    c.object_speed = 6.0;
    return c;
}

// Everything moving, the sphere six times as fast, reversed-Z: wide
// disocclusions for the evaluators' mask tests.
inline rrc_scene::SceneConfig fast_sphere_config(bool jitter) {
    rrc_scene::SceneConfig c;
    c.depth_mode = RRC_DEPTH_MODE_REVERSED;
    c.jitter = jitter;
    c.object_speed = 6.0;
    return c;
}

inline rrc_scene::SceneConfig config_for(const ModeCase& m) {
    rrc_scene::SceneConfig c;
    c.depth_mode = m.mode;
    c.far_plane = m.far_plane;
    return c;
}

// uv of a clip position (double), as CONVENTIONS.md's PREV_CLIP source.
inline glm::dvec2 clip_uv(const float* c) { return glm::dvec2((double(c[0]) / c[3] + 1.0) * 0.5, (double(c[1]) / c[3] + 1.0) * 0.5); }

// A pixel of a frame (its index) and the uv its prev_clip gives.
struct PixelUv {
    size_t k;
    glm::dvec2 uv_prev;
};

// Every pixel of `f` that shows `object`, in row order.
inline std::vector<PixelUv> pixels_of(const rrc_scene::Frame& f, int32_t object) {
    std::vector<PixelUv> out;
    for (size_t k = 0; k < f.object_id.size(); ++k)
        if (f.object_id[k] == object) out.push_back({k, clip_uv(&f.prev_clip[4 * k])});
    return out;
}

inline bool is_background(uint32_t mode, float d) {
    if (mode == RRC_DEPTH_MODE_STANDARD) return d >= 1.0f;
    if (mode == RRC_DEPTH_MODE_REVERSED) return d <= 0.0f;
    return std::isinf(d) || d >= 1e10f;
}

// A minimal double-precision epsilon test (PREV_CLIP source, NDC modes, absolute
// eps) written from docs/CONVENTIONS.md, to produce realistic masks for the
// false-hit evaluator.  Not the project's reference: only a test input.
inline std::vector<uint8_t> epsilon_test_mask(const rrc_scene::Frame& cur, const rrc_scene::Frame& prev, double eps) {
    const int w = cur.width, h = cur.height;
    std::vector<uint8_t> mask(static_cast<size_t>(w) * h, 0);
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            const size_t k = static_cast<size_t>(j) * w + i;
            if (is_background(cur.depth_mode, cur.depth[k])) {
                mask[k] = RRC_MASK_BACKGROUND;
                continue;
            }
            const float* c = &cur.prev_clip[4 * k];
            if (!(c[3] > 0.0f)) continue;
            const glm::dvec2 uv = clip_uv(c);
            if (!(uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0)) continue;
            const rrc_scene::BilinearTaps taps =
                rrc_scene::bilinear_taps(uv * glm::dvec2(w, h), glm::dvec2(cur.prev_jitter[0], cur.prev_jitter[1]), w, h);
            double fetched = 0.0;
            bool any_background = false;
            for (int t = 0; t < 4; ++t) {
                const float d = prev.depth[taps.index(t, w)];
                any_background |= is_background(prev.depth_mode, d);
                fetched += taps.weight[t] * d;
            }
            if (any_background) continue;
            const double diff = fetched - double(c[2]) / c[3];
            if (std::abs(diff) <= eps) mask[k] = RRC_MASK_HIT;
        }
    }
    return mask;
}

}  // namespace rrc_scene_test
