// Self-tests of the analytic scenes: the per-frame inputs must follow
// docs/CONVENTIONS.md, or every kernel test built on them is meaningless.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "scenes/objects.h"
#include "scenes/scene.h"
#include "scenes/selftest_util.h"
#include "scenes/shading.h"

using namespace rrc_scene;
using namespace rrc_scene_test;

namespace {

glm::dmat4 to_mat(const double m[16]) { return glm::make_mat4(m); }

glm::dvec2 sample_uv(const Frame& f, int i, int j) {
    return glm::dvec2((i + 0.5 + f.jitter[0]) / f.width, (j + 0.5 + f.jitter[1]) / f.height);
}

}  // namespace

TEST(SceneJitter, HaltonInRangeAndPeriodic) {
    SceneConfig c;
    c.jitter = true;
    Scene s(c);
    // Index 1 of Halton(2,3) is (1/2, 1/3).
    EXPECT_DOUBLE_EQ(s.jitter(0).x, 0.0);
    EXPECT_DOUBLE_EQ(s.jitter(0).y, 1.0 / 3.0 - 0.5);
    std::vector<glm::dvec2> seen;
    for (int t = -40; t < 1000; ++t) {
        const glm::dvec2 j = s.jitter(t);
        EXPECT_GE(j.x, -0.5);
        EXPECT_LT(j.x, 0.5);
        EXPECT_GE(j.y, -0.5);
        EXPECT_LT(j.y, 0.5);
        EXPECT_EQ(j, s.jitter(t + 16));
        if (t >= 0 && t < 16) seen.push_back(j);
    }
    for (size_t a = 0; a < seen.size(); ++a)
        for (size_t b = a + 1; b < seen.size(); ++b) EXPECT_NE(seen[a], seen[b]);
    const Frame f = s.render(3);
    EXPECT_EQ(f.jitter[0], float(s.jitter(3).x));
    EXPECT_EQ(f.prev_jitter[1], float(s.jitter(2).y));

    c.jitter = false;
    Scene s0(c);
    EXPECT_EQ(s0.jitter(5), glm::dvec2(0.0));
}

TEST(SceneFrame, SceneHasEveryKindOfPixel) {
    Scene s(SceneConfig{});
    const Frame f = s.render(10);
    std::vector<int> count(OBJECT_COUNT + 1, 0);
    for (int32_t id : f.object_id) ++count[id + 1];
    for (int id = -1; id < OBJECT_COUNT; ++id) EXPECT_GT(count[id + 1], 20) << "object " << id;
}

TEST(SceneFrame, StaticSceneReprojectsToItself) {
    for (const ModeCase& m : all_modes()) {
        for (bool jitter : {false, true}) {
            SceneConfig c = config_for(m);
            c.camera_motion = false;
            c.object_motion = false;
            c.jitter = jitter;
            Scene s(c);
            const Frame f = s.render(5), g = s.render(4);
            for (int j = 0; j < f.height; ++j) {
                for (int i = 0; i < f.width; ++i) {
                    const size_t k = size_t(j) * f.width + i;
                    if (f.object_id[k] < 0) continue;
                    const glm::dvec2 uv = clip_uv(&f.prev_clip[4 * k]);
                    const glm::dvec2 us = sample_uv(f, i, j);
                    ASSERT_NEAR(uv.x, us.x, 1e-6) << m.name;
                    ASSERT_NEAR(uv.y, us.y, 1e-6) << m.name;
                    ASSERT_NEAR(f.motion[3 * k], 0.0, 1e-6);
                    ASSERT_NEAR(f.motion[3 * k + 1], 0.0, 1e-6);
                    const double e =
                        m.mode == RRC_DEPTH_MODE_LINEAR ? f.prev_clip[4 * k + 3] : double(f.prev_clip[4 * k + 2]) / f.prev_clip[4 * k + 3];
                    ASSERT_NEAR(e, f.depth[k], 1e-6 * std::max(1.0, double(f.depth[k]))) << m.name;
                    if (!jitter) {
                        // Same camera, same sample: frame t's depth is frame t-1's.
                        ASSERT_EQ(f.depth[k], g.depth[k]);
                        ASSERT_EQ(f.object_id[k], g.object_id[k]);
                    }
                }
            }
        }
    }
}

TEST(SceneFrame, MotionAgreesWithPrevClip) {
    for (const ModeCase& m : all_modes()) {
        SceneConfig c = config_for(m);
        c.jitter = true;
        Scene s(c);
        const Frame f = s.render(12);
        for (int j = 0; j < f.height; ++j) {
            for (int i = 0; i < f.width; ++i) {
                const size_t k = size_t(j) * f.width + i;
                const float* cp = &f.prev_clip[4 * k];
                for (int q = 0; q < 4; ++q) ASSERT_TRUE(std::isfinite(cp[q]));
                for (int q = 0; q < 3; ++q) ASSERT_TRUE(std::isfinite(f.motion[3 * k + q]));
                if (!(cp[3] > 0.0f)) continue;
                const glm::dvec2 mv = clip_uv(cp) - sample_uv(f, i, j);
                ASSERT_NEAR(mv.x, f.motion[3 * k], 1e-5) << m.name << " " << i << "," << j;
                ASSERT_NEAR(mv.y, f.motion[3 * k + 1], 1e-5) << m.name;
                if (f.object_id[k] < 0) continue;
                const double e = m.mode == RRC_DEPTH_MODE_LINEAR ? cp[3] : double(cp[2]) / cp[3];
                ASSERT_NEAR(double(f.depth[k]) + f.motion[3 * k + 2], e, 1e-6 * std::max(1.0, e)) << m.name;
            }
        }
    }
}

TEST(SceneFrame, DepthModesAgreeAfterLinearisation) {
    std::vector<Frame> frames;
    for (const ModeCase& m : all_modes()) frames.push_back(Scene(config_for(m)).render(7));
    const std::vector<ModeCase> modes = all_modes();
    const Frame& ref = frames.back();  // LINEAR
    for (size_t a = 0; a < frames.size(); ++a) {
        const Frame& f = frames[a];
        const double tol = modes[a].mode == RRC_DEPTH_MODE_STANDARD ? 2e-4 : 1e-5;
        for (size_t k = 0; k < f.depth.size(); ++k) {
            ASSERT_EQ(f.object_id[k], ref.object_id[k]);
            ASSERT_EQ(f.linear_depth[k], ref.linear_depth[k]);
            if (f.object_id[k] < 0) {
                const float bg = modes[a].mode == RRC_DEPTH_MODE_STANDARD   ? 1.0f
                                 : modes[a].mode == RRC_DEPTH_MODE_REVERSED ? 0.0f
                                                                            : INFINITY;
                ASSERT_EQ(f.depth[k], bg) << modes[a].name;
                ASSERT_TRUE(is_background(modes[a].mode, f.depth[k]));
                continue;
            }
            ASSERT_FALSE(is_background(modes[a].mode, f.depth[k])) << modes[a].name;
            const double d = linearize_depth(modes[a].mode, f.depth[k], 0.1, modes[a].far_plane);
            ASSERT_NEAR(d / f.linear_depth[k], 1.0, tol) << modes[a].name << " pixel " << k;
        }
    }
}

// The CAMERA reprojection source (CONVENTIONS.md) must give the same previous
// position as prev_clip when nothing moves but the camera.
TEST(SceneFrame, CameraMatricesMatchPrevClip) {
    for (const ModeCase& m : all_modes()) {
        SceneConfig c = config_for(m);
        c.object_motion = false;
        c.jitter = true;
        Scene s(c);
        const Frame f = s.render(20);
        const glm::dmat4 vp = to_mat(f.view_proj), vp_prev = to_mat(f.prev_view_proj);
        EXPECT_EQ(vp, s.view_proj(20));
        const glm::dmat4 inv = glm::inverse(vp);
        const glm::dmat4 mm = vp_prev * inv;
        const glm::dvec4 r(inv[0][3], inv[1][3], inv[2][3], inv[3][3]);  // row 3 of VP^-1
        double worst_px = 0.0;
        for (int j = 0; j < f.height; ++j) {
            for (int i = 0; i < f.width; ++i) {
                const size_t k = size_t(j) * f.width + i;
                if (f.object_id[k] < 0) continue;
                const glm::dvec2 ndc = sample_uv(f, i, j) * 2.0 - 1.0;
                const double d = f.depth[k];
                glm::dvec4 cur;
                if (m.mode == RRC_DEPTH_MODE_LINEAR) {
                    const double a = glm::dot(r, glm::dvec4(ndc, 0.0, 1.0)), b = r.z;
                    cur = glm::dvec4(ndc.x * d, ndc.y * d, (1.0 - d * a) / b, d);
                } else {
                    cur = glm::dvec4(ndc, d, 1.0);
                }
                const glm::dvec4 p = mm * cur;
                const glm::dvec2 uv((p.x / p.w + 1.0) * 0.5, (p.y / p.w + 1.0) * 0.5);
                const glm::dvec2 ref = clip_uv(&f.prev_clip[4 * k]);
                worst_px = std::max(worst_px, std::abs(uv.x - ref.x) * f.width);
                worst_px = std::max(worst_px, std::abs(uv.y - ref.y) * f.height);
            }
        }
        EXPECT_LT(worst_px, 1e-3) << m.name;
    }
}

TEST(SceneFrame, ConsecutiveFramesShareMatrices) {
    SceneConfig c;
    c.jitter = true;
    Scene s(c);
    const Frame a = s.render(8), b = s.render(9);
    for (int q = 0; q < 16; ++q) EXPECT_EQ(b.prev_view_proj[q], a.view_proj[q]);
    EXPECT_EQ(b.prev_jitter[0], a.jitter[0]);
    EXPECT_EQ(b.prev_jitter[1], a.jitter[1]);
    // Skipped frames: the previous frame may be any frame.
    const Frame skip = s.render(12, 8);
    for (int q = 0; q < 16; ++q) EXPECT_EQ(skip.prev_view_proj[q], a.view_proj[q]);
    EXPECT_EQ(skip.prev_index, 8);
}

TEST(SceneFrame, DepthQuantisation) {
    for (uint32_t fmt : {uint32_t(RRC_DEPTH_FORMAT_UNORM16), uint32_t(RRC_DEPTH_FORMAT_UNORM24)}) {
        const double steps = fmt == RRC_DEPTH_FORMAT_UNORM16 ? 65535.0 : 16777215.0;
        SceneConfig c;
        c.depth_mode = RRC_DEPTH_MODE_REVERSED;
        Scene exact(c);
        c.depth_format = fmt;
        Scene quant(c);
        const Frame fe = exact.render(4), fq = quant.render(4);
        int changed = 0;
        for (size_t k = 0; k < fq.depth.size(); ++k) {
            if (fq.object_id[k] < 0) continue;
            const double z = quant.projection().ndc_z(fq.linear_depth[k]);
            ASSERT_EQ(fq.depth[k], float(std::nearbyint(z * steps) / steps));
            ASSERT_LE(std::abs(double(fq.depth[k]) - fe.depth[k]), 0.5 / steps + 1e-7);
            changed += fq.depth[k] != fe.depth[k];
        }
        EXPECT_GT(changed, 100);
    }
}

TEST(SceneFrame, MovingSphereLandsOnItselfInPreviousFrame) {
    SceneConfig c;
    c.jitter = true;
    Scene s(c);
    const int t = 10;
    const Frame f = s.render(t);
    const std::vector<int32_t> prev_ids = s.object_ids(t - 1);
    SceneConfig still = c;
    still.object_motion = false;
    const Frame g = Scene(still).render(t);
    int total = 0, on_sphere = 0;
    double object_motion_px = 0.0;
    for (const PixelUv& p : pixels_of(f, OBJECT_SPHERE_MOVING)) {
        const size_t k = p.k;
        const glm::dvec2 uv = p.uv_prev;
        // Nearest texel of the previous frame (CONVENTIONS.md).
        const int x = std::clamp(int(std::floor(uv.x * f.width - f.prev_jitter[0])), 0, f.width - 1);
        const int y = std::clamp(int(std::floor(uv.y * f.height - f.prev_jitter[1])), 0, f.height - 1);
        ++total;
        on_sphere += prev_ids[size_t(y) * f.width + x] == OBJECT_SPHERE_MOVING;
        if (g.object_id[k] == OBJECT_SPHERE_MOVING)
            object_motion_px = std::max(object_motion_px, std::abs(double(f.motion[3 * k]) - g.motion[3 * k]) * f.width);
    }
    ASSERT_GT(total, 50);
    EXPECT_GE(on_sphere, 0.9 * total);
    EXPECT_GT(object_motion_px, 0.3);  // the sphere's own motion is visible in its vectors
}

TEST(SceneSignals, TruthBoundedNoiseZeroMeanDeterministic) {
    SceneConfig c;
    c.noise_amplitude = 0.25;
    Scene s(c);
    double sum = 0.0;
    long n = 0;
    for (int t = 0; t < 4; ++t) {
        const Frame f = s.render(t);
        const Frame again = s.render(t);
        ASSERT_EQ(0, std::memcmp(f.signal4.data(), again.signal4.data(), f.signal4.size() * sizeof(float)));
        for (size_t k = 0; k < f.truth1.size(); ++k) {
            ASSERT_GE(f.truth1[k], 0.0f);
            ASSERT_LE(f.truth1[k], 1.0f);
            ASSERT_LE(std::abs(f.signal1[k] - f.truth1[k]), 0.25f + 1e-6f);
            if (f.object_id[k] < 0) {
                ASSERT_EQ(f.signal1[k], float(kSky1));
                ASSERT_EQ(f.signal4[4 * k + 2], float(sky4()[2]));
                continue;
            }
            sum += double(f.signal1[k]) - f.truth1[k];
            ++n;
            for (int q = 0; q < 4; ++q) {
                ASSERT_GE(f.truth4[4 * k + q], 0.0f);
                ASSERT_LE(f.truth4[4 * k + q], 1.0f);
                ASSERT_LE(std::abs(f.signal4[4 * k + q] - f.truth4[4 * k + q]), 0.25f + 1e-6f);
                sum += double(f.signal4[4 * k + q]) - f.truth4[4 * k + q];
                ++n;
            }
        }
    }
    // Uniform(-a, a) has sd a/sqrt(3) = 0.144: the mean of ~100k samples is within 0.003.
    EXPECT_NEAR(sum / n, 0.0, 0.003);

    SceneConfig c2 = c;
    c2.seed = 2;
    const Frame a = s.render(1), b = Scene(c2).render(1);
    EXPECT_NE(0, std::memcmp(a.signal1.data(), b.signal1.data(), a.signal1.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(a.truth1.data(), b.truth1.data(), a.truth1.size() * sizeof(float)));
}

TEST(SceneSignals, TruthSticksToTheSurface) {
    // Static camera: a moving-sphere pixel's truth equals the truth of its
    // object-space point, which the previous frame showed at uv_prev.
    SceneConfig c;
    c.camera_motion = false;
    Scene s(c);
    const Frame f = s.render(6);
    int checked = 0;
    for (const PixelUv& p : pixels_of(f, OBJECT_SPHERE_MOVING)) {
        const size_t k = p.k;
        const Hit h = s.cast(5, p.uv_prev.x * f.width, p.uv_prev.y * f.height);
        ASSERT_EQ(f.truth1[k], float(shade1(OBJECT_SPHERE_MOVING, f.object_pos[k])));
        // Hidden then (behind the sphere's own front, near its silhouette)?
        if (h.object_id != OBJECT_SPHERE_MOVING || glm::length(h.object - f.object_pos[k]) > 1e-3) continue;
        // The same object-space point (up to fp32 prev_clip), so the same truth.
        ASSERT_NEAR(shade1(h.object_id, h.object), f.truth1[k], 1e-3);
        ++checked;
    }
    EXPECT_GT(checked, 50);
}

TEST(SceneSignals, InvalidSampleInjection) {
    SceneConfig c;
    c.invalid_fraction = 0.1;
    Scene s(c);
    const Frame f = s.render(3);
    const size_t n = f.signal1.size();
    size_t bad1 = 0, bad4 = 0, nan = 0, pinf = 0, ninf = 0;
    for (size_t k = 0; k < n; ++k) {
        const float v = f.signal1[k];
        if (!std::isfinite(v)) {
            ++bad1;
            nan += std::isnan(v);
            pinf += v == INFINITY;
            ninf += v == -INFINITY;
        }
        int comps = 0;
        for (int q = 0; q < 4; ++q) comps += !std::isfinite(f.signal4[4 * k + q]);
        ASSERT_LE(comps, 1);
        bad4 += comps;
        ASSERT_TRUE(std::isfinite(f.truth1[k]));
    }
    EXPECT_NEAR(double(bad1) / n, 0.1, 0.02);
    EXPECT_NEAR(double(bad4) / n, 0.1, 0.02);
    EXPECT_GT(nan, 0u);
    EXPECT_GT(pinf, 0u);
    EXPECT_GT(ninf, 0u);

    const Frame clean = Scene(SceneConfig{}).render(3);
    for (float v : clean.signal4) ASSERT_TRUE(std::isfinite(v));
}

TEST(SceneConfigTest, RejectsBadConfigurations) {
    SceneConfig c;
    c.width = 0;
    EXPECT_THROW(Scene{c}, std::invalid_argument);
    c = SceneConfig{};
    c.near_plane = 0.0;
    EXPECT_THROW(Scene{c}, std::invalid_argument);
    c = SceneConfig{};
    c.far_plane = 0.05;
    EXPECT_THROW(Scene{c}, std::invalid_argument);
    c = SceneConfig{};
    c.depth_mode = 7;
    EXPECT_THROW(Scene{c}, std::invalid_argument);
}

TEST(SceneFrame, LinearBackgroundValue) {
    SceneConfig c;
    c.depth_mode = RRC_DEPTH_MODE_LINEAR;
    c.linear_background = 1e10f;
    const Frame f = Scene(c).render(0);
    for (size_t k = 0; k < f.depth.size(); ++k)
        if (f.object_id[k] < 0) {
            ASSERT_EQ(f.depth[k], 1e10f);
        }
}

// The time a frame takes is printed for a reader, not asserted: a loaded
// machine or a sanitizer build takes any time (tests/lint/timed_assertions.py).
TEST(SceneFrame, RenderTimeIsPrinted) {
    Scene s(SceneConfig{});
    const auto t0 = std::chrono::steady_clock::now();
    for (int t = 0; t < 5; ++t) (void)s.render(t);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / 5;
    std::printf("96x64 frame: %.2f ms\n", ms);
}
