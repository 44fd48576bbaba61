// The ADAPTIVE test of docs/CONVENTIONS.md on hand-made PREV_CLIP frames whose
// widening can be worked out by hand: a parabola in x (curvature), a plane
// (only the fp32 position term), a card step (none), a step beside the
// parabola (its smooth side's curvature), a two-pixel card (none) and object
// ids.
#include <gtest/gtest.h>

#include <cmath>

#include "selftest_scene.h"

using rrc_ref::FrameResult;
using rrc_ref_test::Scene;

namespace {

constexpr double kK = 0x1p-10;  // curvature: D(x) = 0.5 + k x^2, exact in fp32

// The fp32 position term on an 8-wide frame with slope `sx` along x and none along y.
double position_term(double sx) { return 8 * 0x1p-24 * 8 * sx; }

// 8x3 STANDARD FLOAT32 frame whose previous positions are half a texel to the
// right (fx = 0.5, fy = 0) and whose expected depth is `e(i)`; the previous
// depth equals the current one.
template <typename Depth, typename Expected>
Scene shifted(Depth depth, Expected e, rrc_depth_test test) {
    Scene s(8, 3, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_PREV_CLIP);
    s.ctx.depth_test = test;
    s.add_channel(1, 0.5f);
    for (int j = 0; j < s.H; ++j)
        for (int i = 0; i < s.W; ++i) {
            const size_t k = s.at(i, j);
            s.depth[k] = (float)depth(i);
            const double u = (i + 1.0) / s.W, v = (j + 0.5) / s.H;  // q.x = i + 1: half a texel right of centre i + 0.5
            s.reprojection[4 * k + 0] = (float)(2 * u - 1);
            s.reprojection[4 * k + 1] = (float)(2 * v - 1);
            s.reprojection[4 * k + 2] = (float)e(i);
            s.reprojection[4 * k + 3] = 1.0f;
        }
    return s;
}

FrameResult run(Scene& s) { return s.run(s.previous({std::vector<float>(s.size(), 1.0f)}, 1)); }

double parabola(int i) { return 0.5 + kK * i * i; }
double parabola_at_half(int i) { return 0.5 + kK * (i + 0.5) * (i + 0.5); }  // the surface's exact depth at q

}  // namespace

TEST(Adaptive, CurvatureWidensByTheResidualBound) {
    for (rrc_depth_test test : {RRC_DEPTH_TEST_FIXED, RRC_DEPTH_TEST_DEFAULT}) {
        Scene s = shifted(parabola, parabola_at_half, test);
        FrameResult r = run(s);
        const size_t k = s.at(4, 1);
        // The fetch is (D4 + D5)/2, off the surface by k/4 = 2^-12 (the Taylor residual f(1-f) D''/2).
        EXPECT_DOUBLE_EQ(r.diff[k], 0x1p-12);
        const double paper = 4 * 0x1p-24;  // 4 ulp of e in [0.5, 1)
        if (test == RRC_DEPTH_TEST_FIXED) {
            EXPECT_DOUBLE_EQ(r.eps[k], paper);
            EXPECT_EQ(r.mask[k], 0) << "the paper's epsilon misses the curved surface";
        } else {
            // s = 2k on x (its neighbours too: no step), 0 on y; noise 4 ulp(D5) = 2^-22;
            // W = GAIN * (0.25 + 0) * (2k - 2^-22), plus the position term at slope min(7k, 9k).
            EXPECT_DOUBLE_EQ(r.eps[k], paper + 2.0 * 0.25 * (2 * kK - 0x1p-22) + position_term(7 * kK));
            EXPECT_EQ(r.mask[k], RRC_MASK_HIT);
        }
    }
}

TEST(Adaptive, PlaneKeepsThePapersEpsilon) {
    auto plane = [](int i) { return 0.5 + 0x1p-8 * i; };
    auto plane_at_half = [](int i) { return 0.5 + 0x1p-8 * (i + 0.5); };
    Scene s = shifted(plane, plane_at_half, RRC_DEPTH_TEST_DEFAULT);
    FrameResult r = run(s);
    for (int i = 0; i < 7; ++i) {  // column 7's fetch clamps at the edge
        const size_t k = s.at(i, 1);
        // The plane's slope is 2^-8 at every column (the first: its one existing difference).
        EXPECT_DOUBLE_EQ(r.eps[k], 4 * rrc_ref::ulp_fp32(plane_at_half(i)) + position_term(0x1p-8)) << i;
        EXPECT_EQ(r.mask[k], RRC_MASK_HIT) << i;
    }
    // Beyond the last texel centre the taps clamp: the fetch is off by the
    // slope times the overhang (0.5 texel), and the slope term covers it.
    const size_t k = s.at(7, 1);
    EXPECT_DOUBLE_EQ(r.diff[k], -0x1p-8 * 0.5);
    EXPECT_DOUBLE_EQ(r.eps[k], 4 * rrc_ref::ulp_fp32(plane_at_half(7)) + 2.0 * 0.5 * 0x1p-8 + position_term(0x1p-8));
    EXPECT_EQ(r.mask[k], RRC_MASK_HIT);
}

TEST(Adaptive, StepIsNotWidened) {
    // A card 2^-8 nearer from column 5 on; every pixel expects the wall, as
    // if the card had moved away and revealed it.
    auto card = [](int i) { return i >= 5 ? 0.5 - 0x1p-8 : 0.5; };
    auto wall = [](int) { return 0.5; };
    Scene s = shifted(card, wall, RRC_DEPTH_TEST_DEFAULT);
    FrameResult r = run(s);
    const size_t k = s.at(4, 1);          // taps 4 (wall) and 5 (card): a step from both sides
    EXPECT_DOUBLE_EQ(r.eps[k], 0x1p-22);  // 4 ulp of e = 0.5, the paper's epsilon (slope min(2^-8, 0) = 0: no position term)
    EXPECT_EQ(r.mask[k], 0);
    const size_t k5 = s.at(5, 1);  // on the card, taps 5 and 6 on the card, expects the wall
    EXPECT_EQ(r.mask[k5], 0);
}

TEST(Adaptive, StepTakesItsSmoothSidesCurvature) {
    // A far wall up to column 2, the parabola from column 3 on: pixel 3 is a
    // step of its own (s = 0.25 - 2k next to s- = -0.25 + 9k), its fetch at
    // q.x = 4 lies on the parabola, and its smooth side s+ = 2k is the
    // parabola's curvature, which the widening takes (as on a column beside
    // its silhouette).
    auto depth = [](int i) { return i <= 2 ? 0.75 : parabola(i); };
    Scene s = shifted(depth, parabola_at_half, RRC_DEPTH_TEST_DEFAULT);
    FrameResult r = run(s);
    const size_t k = s.at(3, 1);
    EXPECT_DOUBLE_EQ(r.diff[k], 0x1p-12);  // (D3 + D4)/2 against the surface at 3.5, as in the parabola's middle
    // noise 4 ulp(0.75) = 2^-22; y: no second difference; slope min(7k, 0.25 - 9k) = 7k.
    EXPECT_DOUBLE_EQ(r.eps[k], 4 * 0x1p-24 + 2.0 * 0.25 * (2 * kK - 0x1p-22) + position_term(7 * kK));
    EXPECT_EQ(r.mask[k], RRC_MASK_HIT);
}

TEST(Adaptive, TwoPixelSliverIsNotWidened) {
    // A card two columns wide (4 and 5) 2^-8 in front of the wall; every
    // pixel expects the wall.  At pixel 4 the far side's second difference
    // (+h, the card's other edge) has the step's own size: it is no smooth
    // side, so the card is not widened by its own height.
    auto card = [](int i) { return i == 4 || i == 5 ? 0.5 - 0x1p-8 : 0.5; };
    auto wall = [](int) { return 0.5; };
    Scene s = shifted(card, wall, RRC_DEPTH_TEST_DEFAULT);
    FrameResult r = run(s);
    const size_t k = s.at(4, 1);  // taps 4 and 5, both on the card
    EXPECT_DOUBLE_EQ(r.diff[k], -0x1p-8);
    EXPECT_DOUBLE_EQ(r.eps[k], 0x1p-22);  // the paper's epsilon: no curvature, slope min(2^-8, 0) = 0
    EXPECT_EQ(r.mask[k], 0);
}

TEST(Adaptive, ObjectIdsRejectForeignTaps) {
    Scene s = shifted(parabola, parabola_at_half, RRC_DEPTH_TEST_DEFAULT);
    s.ctx.use_object_id = 1;
    std::vector<uint32_t> ids(s.size(), 7);
    for (int j = 0; j < s.H; ++j) ids[s.at(5, j)] = 9;  // column 5 is another object
    s.frame.object_id = ids.data();
    rrc_ref::PreviousFrame prev = s.previous({std::vector<float>(s.size(), 1.0f)}, 1);
    prev.object_id = ids;
    FrameResult r = s.run(prev);
    EXPECT_EQ(r.mask[s.at(4, 1)], 0) << "tap 5 (weight 0.5) is object 9";
    EXPECT_EQ(r.mask[s.at(3, 1)], RRC_MASK_HIT) << "taps 3 and 4 are object 7";
    EXPECT_EQ(r.mask[s.at(5, 1)], 0) << "pixel 5 (object 9) with tap 6 on object 7";
}
