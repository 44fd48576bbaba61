// Whole frames of the reference on small hand-made scenes: hit/miss
// classification, background, invalid data, jitter and the sources.
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <stdexcept>

#include "selftest_scene.h"

using rrc_ref::FrameResult;
using rrc_ref::PreviousFrame;
using rrc_ref_test::Scene;

namespace {

// 8x6 static scene seen by an identity CAMERA: a tilted plane of NDC depth,
// one fp32 channel with lambda 0.6, history 10 + i at age 3.
struct Static {
    Scene s{8, 6, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_CAMERA};
    std::vector<float> history;
    double lambda = 0.6f;
    explicit Static(rrc_depth_format format = RRC_DEPTH_FORMAT_UNORM16) {
        s.ctx.depth_format = format;
        s.add_channel(1, 0.6f);
        history.resize(s.size());
        for (int j = 0; j < s.H; ++j)
            for (int i = 0; i < s.W; ++i) {
                s.depth[s.at(i, j)] = 0.3f + 0.01f * i + 0.02f * j;
                s.samples[0][s.at(i, j)] = 0.1f * i + j;
                history[s.at(i, j)] = 10.0f + i;
            }
    }
    PreviousFrame prev() const { return s.previous({history}, 3); }
    double blend(size_t k) const { return lambda * history[k] + (1 - lambda) * s.samples[0][k]; }
};

// A one-row scene of the tests below: STANDARD depth in UNORM16, one fp32
// channel with lambda 0.5.
Scene unorm16_row(int width, rrc_reprojection source) {
    Scene s(width, 1, RRC_DEPTH_MODE_STANDARD, source);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    s.add_channel(1, 0.5f);
    return s;
}

// The mask of pixels 0, 1, ... in order.
void expect_masks(const FrameResult& r, std::initializer_list<int> masks) {
    size_t i = 0;
    for (int m : masks) {
        EXPECT_EQ(r.mask[i], m) << "pixel " << i;
        ++i;
    }
}

}  // namespace

TEST(Frame, StaticIdentityCameraHitsEverywhere) {
    Static st;
    FrameResult r = st.s.run(st.prev());
    for (size_t k = 0; k < st.s.size(); ++k) {
        EXPECT_EQ(r.mask[k], RRC_MASK_HIT) << k;
        EXPECT_NEAR(r.channels[0].out[k], st.blend(k), 1e-12) << k;
        EXPECT_EQ(r.channels[0].age[k], 4) << k;
        EXPECT_EQ(r.near_threshold[k], 0) << k;     // UNORM16 eps is far above fp32 noise
        EXPECT_EQ(r.near_nearest_edge[k], 0) << k;  // q at texel centres
        EXPECT_NEAR(r.diff[k], 0.0, 1e-12) << k;
        // The paper's epsilon plus, under the ADAPTIVE default, only the fp32
        // allowances on this plane: the position term POSITION_ULPS 2^-24 (W |dz/dx| + H |dz/dy|)
        // and CAMERA's CAMERA_ULPS 2^-24 |z| (an identity M).
        EXPECT_NEAR(r.eps[k], 1.0 / 65535.0 + 8 * 0x1p-24 * (8 * 0.01 + 6 * 0.02) + 4 * 0x1p-24 * st.s.depth[k], 1e-9) << k;
    }
    EXPECT_EQ(r.stats.hits, st.s.size());
    EXPECT_EQ(r.stats.misses, 0u);
}

TEST(Frame, StaticFloat32DepthHitsToo) {
    Static st(RRC_DEPTH_FORMAT_FLOAT32);
    FrameResult r = st.s.run(st.prev());
    for (size_t k = 0; k < st.s.size(); ++k) {
        EXPECT_EQ(r.mask[k], RRC_MASK_HIT) << k;
        EXPECT_NEAR(r.eps[k], 4 * rrc_ref::ulp_fp32(st.s.depth[k]) + 8 * 0x1p-24 * (8 * 0.01 + 6 * 0.02) + 4 * 0x1p-24 * st.s.depth[k],
                    1e-9)
            << k;  // as above
    }
}

TEST(Frame, FirstFrameAndResetMissEverywhere) {
    Static st;
    FrameResult first = st.s.run(PreviousFrame{});
    st.s.frame.reset = 1;
    FrameResult reset = st.s.run(st.prev());
    for (const FrameResult* r : {&first, &reset}) {
        for (size_t k = 0; k < st.s.size(); ++k) {
            EXPECT_EQ(r->mask[k], 0) << k;
            EXPECT_EQ(r->channels[0].out[k], st.s.samples[0][k]) << k;
            EXPECT_EQ(r->channels[0].age[k], 1) << k;
            EXPECT_TRUE(std::isnan(r->diff[k])) << k;
        }
        EXPECT_EQ(r->stats.misses, st.s.size());
    }
}

TEST(Frame, BackgroundPixelAndItsTaps) {
    Static st;
    st.s.depth[st.s.at(3, 2)] = 1.0f;  // far plane: background, now and in the previous frame
    FrameResult r = st.s.run(st.prev());
    size_t bg = st.s.at(3, 2);
    EXPECT_EQ(r.mask[bg], RRC_MASK_BACKGROUND);
    EXPECT_EQ(r.channels[0].out[bg], st.s.samples[0][bg]);
    EXPECT_EQ(r.channels[0].age[bg], 0);
    // Pixels whose four bilinear taps (x0..x0+1, y0..y0+1 with q at texel
    // centres: f = 0) include (3, 2) miss even though that tap's weight is 0.
    for (auto [i, j] : {std::pair{2, 2}, {3, 1}, {2, 1}}) {
        size_t k = st.s.at(i, j);
        EXPECT_EQ(r.mask[k], 0) << i << "," << j;
        EXPECT_EQ(r.channels[0].age[k], 1);
        EXPECT_EQ(r.near_threshold[k], 1);  // a position error of 1e-7 texel moves the taps
    }
    EXPECT_EQ(r.mask[st.s.at(4, 2)], RRC_MASK_HIT);
    EXPECT_EQ(r.mask[st.s.at(3, 3)], RRC_MASK_HIT);
    EXPECT_EQ(r.stats.background, 1u);
    EXPECT_EQ(r.stats.misses, 3u);
    EXPECT_EQ(r.stats.hits, st.s.size() - 4);
}

TEST(Frame, InvalidSamples) {
    Static st;
    st.s.depth[st.s.at(5, 5)] = 1.0f;  // background
    st.s.samples[0][st.s.at(1, 1)] = NAN;
    st.s.samples[0][st.s.at(5, 5)] = INFINITY;
    FrameResult hit = st.s.run(st.prev());
    size_t k = st.s.at(1, 1);
    EXPECT_EQ(hit.mask[k], RRC_MASK_HIT | RRC_MASK_INVALID_SAMPLE);
    EXPECT_EQ(hit.channels[0].out[k], st.history[k]);  // H unchanged
    EXPECT_EQ(hit.channels[0].age[k], 3);              // n_prev
    k = st.s.at(5, 5);
    EXPECT_EQ(hit.mask[k], RRC_MASK_BACKGROUND | RRC_MASK_INVALID_SAMPLE);
    EXPECT_EQ(hit.channels[0].out[k], 0.0);
    EXPECT_EQ(hit.channels[0].age[k], 0);
    EXPECT_EQ(hit.stats.invalid_samples, 2u);
    FrameResult miss = st.s.run(PreviousFrame{});
    k = st.s.at(1, 1);
    EXPECT_EQ(miss.mask[k], RRC_MASK_INVALID_SAMPLE);
    EXPECT_EQ(miss.channels[0].out[k], 0.0);
    EXPECT_EQ(miss.channels[0].age[k], 0);
}

TEST(Frame, DoNotCacheMaskForcesMisses) {
    Static st;
    st.s.ctx.use_nocache_mask = 1;
    st.s.nocache[st.s.at(2, 2)] = 1;
    FrameResult r = st.s.run(st.prev());
    EXPECT_EQ(r.mask[st.s.at(2, 2)], 0);
    EXPECT_EQ(r.channels[0].age[st.s.at(2, 2)], 1);
    EXPECT_EQ(r.mask[st.s.at(2, 3)], RRC_MASK_HIT);
}

TEST(Frame, InvalidGeometry) {
    Scene s(6, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_MOTION);
    s.add_channel(1, 0.5f);
    s.depth = {NAN, -0.1f, INFINITY, 0.5f, 1.0f, 0.5f};
    s.reprojection[2 * 3] = NAN;      // pixel 3: non-finite motion
    s.reprojection[2 * 4 + 1] = NAN;  // pixel 4: background wins over bad motion
    for (int i = 0; i < 6; ++i) s.samples[0][i] = 7.0f;
    PreviousFrame prev = s.previous({std::vector<float>(6, 1.0f)}, 2);
    prev.depth.assign(6, 0.5f);
    FrameResult r = s.run(prev);
    for (int i : {0, 1, 2, 3}) {
        EXPECT_EQ(r.mask[i], RRC_MASK_INVALID_GEOMETRY) << i;
        EXPECT_EQ(r.channels[0].out[i], 7.0) << i;
        EXPECT_EQ(r.channels[0].age[i], 1) << i;
    }
    EXPECT_EQ(r.mask[4], RRC_MASK_BACKGROUND);
    EXPECT_EQ(r.mask[5], RRC_MASK_HIT);
    EXPECT_EQ(r.stats.invalid_geometry, 4u);
}

TEST(Frame, LinearBackgroundAndInvalidDepth) {
    Scene s(5, 1, RRC_DEPTH_MODE_LINEAR, RRC_REPROJECTION_MOTION);
    s.ctx.background_threshold = 100.0f;
    s.add_channel(1, 0.5f);
    s.depth = {INFINITY, 150.0f, 0.0f, -INFINITY, 99.0f};
    FrameResult r = s.run(PreviousFrame{});
    expect_masks(r, {RRC_MASK_BACKGROUND, RRC_MASK_BACKGROUND, RRC_MASK_INVALID_GEOMETRY, RRC_MASK_INVALID_GEOMETRY, 0});
}

TEST(Frame, UvPrevOnAndOutsideTheBorder) {
    // PREV_CLIP, w = 2: pixel 0 lands just left of uv 0, pixel 1 exactly on
    // uv_x = 1 (closed square: a hit), pixel 2 in the middle.
    Scene s = unorm16_row(3, RRC_REPROJECTION_PREV_CLIP);
    float xs[3] = {2.0f * (-1.0f - 2e-6f), 2.0f, 0.0f};
    for (int i = 0; i < 3; ++i) {
        float* c = &s.reprojection[4 * i];
        c[0] = xs[i], c[1] = 0.0f, c[2] = 1.0f, c[3] = 2.0f;  // z/w = 0.5 = the depth
    }
    PreviousFrame prev = s.previous({std::vector<float>(3, 1.0f)}, 1);
    FrameResult r = s.run(prev);
    EXPECT_LT(r.uv_prev_x[0], 0.0);
    EXPECT_EQ(r.mask[0], 0);
    EXPECT_EQ(r.near_threshold[0], 0);  // 1e-6 is far beyond fp32 error
    EXPECT_EQ(r.uv_prev_x[1], 1.0);
    EXPECT_EQ(r.mask[1], RRC_MASK_HIT);
    EXPECT_EQ(r.near_threshold[1], 1);  // exactly on the border: the kernel may round out
    EXPECT_EQ(r.mask[2], RRC_MASK_HIT);
    EXPECT_EQ(r.near_threshold[2], 0);
}

TEST(Frame, NonPositiveClipWMisses) {
    Scene s = unorm16_row(3, RRC_REPROJECTION_PREV_CLIP);
    float clips[3][4] = {{0, 0, -1, -2}, {0, 0, 0, 0}, {0, 0, 1, 2}};  // behind, at, in front
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 4; ++k) s.reprojection[4 * i + k] = clips[i][k];
    FrameResult r = s.run(s.previous({std::vector<float>(3, 1.0f)}, 1));
    expect_masks(r, {0, 0, RRC_MASK_HIT});
    EXPECT_EQ(r.near_threshold[0] + r.near_threshold[1], 0);  // w is an input: exact
}

TEST(Frame, JitterIsRemovedBeforeReprojecting) {
    Scene s = unorm16_row(8, RRC_REPROJECTION_MOTION);
    std::vector<float> history(8);
    for (int i = 0; i < 8; ++i) history[i] = static_cast<float>(i), s.samples[0][i] = 100.0f;
    PreviousFrame prev = s.previous({history}, 1);
    s.frame.jitter[0] = 0.25f;
    s.frame.prev_jitter[0] = 0.25f;  // same sample positions: texel centres again
    FrameResult same = s.run(prev);
    s.frame.prev_jitter[0] = 0.0f;  // previous texel i' shows i' + 0.5: q = i + 0.75
    FrameResult shifted = s.run(prev);
    for (int i = 0; i < 8; ++i) {
        EXPECT_DOUBLE_EQ(same.uv_prev_x[i], (i + 0.75) / 8) << i;
        EXPECT_EQ(same.mask[i], RRC_MASK_HIT);
        EXPECT_NEAR(same.channels[0].out[i], 0.5 * i + 50.0, 1e-12) << i;
        double h = std::min(i + 0.25, 7.0);  // clamped at the right edge
        EXPECT_NEAR(shifted.channels[0].out[i], 0.5 * h + 50.0, 1e-12) << i;
    }
}

TEST(Frame, NearestEdgeFlagAtIntegerSampleCoordinates) {
    Scene s(8, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_MOTION);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    s.add_channel(1, 0.5f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_NEAREST);
    for (int i = 0; i < 8; ++i) s.reprojection[2 * i] = (i < 4 ? 0.5f : 0.25f) / 8;
    FrameResult r = s.run(s.previous({std::vector<float>(8, 1.0f)}, 1));
    for (int i = 1; i < 7; ++i) {
        EXPECT_EQ(r.mask[i], RRC_MASK_HIT) << i;
        EXPECT_EQ(r.near_nearest_edge[i], i < 4 ? 1 : 0) << i;  // q = i + 1 vs i + 0.75
    }
}

TEST(Frame, PlainMotionRelativeTestOnLinearDepth) {
    Scene s(2, 1, RRC_DEPTH_MODE_LINEAR, RRC_REPROJECTION_MOTION);
    s.add_channel(1, 0.5f);
    s.depth = {10.0f, 10.0f};
    PreviousFrame prev = s.previous({std::vector<float>(2, 1.0f)}, 1);
    prev.depth = {10.05f, 10.2f};  // within tau = 1% / beyond it
    FrameResult r = s.run(prev);
    EXPECT_EQ(r.mask[0], RRC_MASK_HIT);
    EXPECT_NEAR(r.fetched[0], 10.05f, 1e-12);
    EXPECT_NEAR(r.eps[0], 0.1, 1e-15);
    EXPECT_EQ(r.mask[1], 0);
    s.ctx.tau = 0.05f;
    EXPECT_EQ(s.run(prev).mask[1], RRC_MASK_HIT);
}

TEST(Frame, PlainMotionLinearisesStandardDepth) {
    Scene s(2, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_MOTION);
    s.ctx.near_plane = 0.1f;
    s.ctx.far_plane = 100.0f;
    s.add_channel(1, 0.5f);
    double n = s.ctx.near_plane, f = s.ctx.far_plane;
    auto z_of = [&](double d) { return static_cast<float>((f - n * f / d) / (f - n)); };
    s.depth = {z_of(10.0), z_of(10.0)};
    PreviousFrame prev = s.previous({std::vector<float>(2, 1.0f)}, 1);
    prev.depth = {z_of(10.05), z_of(10.2)};
    FrameResult r = s.run(prev);
    EXPECT_NEAR(r.expected[0], 10.0, 1e-4);  // linear, up to the float rounding of z
    EXPECT_NEAR(r.fetched[0], 10.05, 1e-4);
    EXPECT_EQ(r.mask[0], RRC_MASK_HIT);
    EXPECT_EQ(r.mask[1], 0);
}

TEST(Frame, MotionDepthExpectsDepthPlusChange) {
    Scene s = unorm16_row(2, RRC_REPROJECTION_MOTION_DEPTH);
    s.depth = {0.5f, 0.5f};
    s.reprojection = {0, 0, 0.001f, 0, 0, 0};  // pixel 0 knows its depth change
    PreviousFrame prev = s.previous({std::vector<float>(2, 1.0f)}, 1);
    prev.depth = {0.501f, 0.501f};
    FrameResult r = s.run(prev);
    EXPECT_NEAR(r.expected[0], 0.501, 1e-7);
    EXPECT_EQ(r.mask[0], RRC_MASK_HIT);
    EXPECT_EQ(r.mask[1], 0);  // 0.001 apart, eps = 1/65535
}

TEST(Frame, MotionScaleConvertsPixelVectors) {
    Scene s(8, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_MOTION);
    s.ctx.motion_scale[0] = 1.0f / 8;
    s.ctx.motion_scale[1] = 1.0f;
    s.add_channel(1, 0.5f);
    for (int i = 0; i < 8; ++i) s.reprojection[2 * i] = -1.5f;  // pixels, leftwards
    FrameResult r = s.run(PreviousFrame{});
    EXPECT_DOUBLE_EQ(r.uv_prev_x[4], (4.5 - 1.5) / 8);
    EXPECT_DOUBLE_EQ(r.uv_prev_y[4], 0.5);
}

TEST(Frame, EpsilonBoundaryIsInclusive) {
    Scene s(2, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_PREV_CLIP);
    s.ctx.epsilon = 0.25f;  // absolute epsilon
    s.add_channel(1, 0.5f);
    for (int i = 0; i < 2; ++i) {
        float* c = &s.reprojection[4 * i];
        c[0] = 0.0f, c[1] = 0.0f, c[2] = 0.5f, c[3] = 1.0f;  // centre, e = 0.5
    }
    PreviousFrame prev = s.previous({std::vector<float>(2, 1.0f)}, 1);
    prev.depth = {0.75f, 0.75f};  // diff = 0.25 = eps exactly
    FrameResult r = s.run(prev);
    EXPECT_EQ(r.diff[0], 0.25);
    EXPECT_EQ(r.mask[0], RRC_MASK_HIT);
    EXPECT_EQ(r.near_threshold[0], 1);
    prev.depth = {0.7500001f, 0.7500001f};
    EXPECT_EQ(s.run(prev).mask[0], 0);
}

TEST(Frame, MismatchedPreviousFrameIsRefused) {
    Scene s(2, 2, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_MOTION);
    s.add_channel(1, 0.5f);
    PreviousFrame prev = s.previous({std::vector<float>(3, 1.0f)}, 1);  // 3 != 4 texels
    EXPECT_THROW(s.run(prev), std::invalid_argument);
    prev.valid = false;  // not read at all
    EXPECT_NO_THROW(s.run(prev));
}
