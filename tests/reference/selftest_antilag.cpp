// The lag detector of the reference (finish.h, docs/CONVENTIONS.md "The lag
// detector") against hand-computed cases: the relative gap, the confidence's
// ramp, the shortened age and the lambda_eff it caps, where it applies.
#include <gtest/gtest.h>

#include <cmath>

#include "finish.h"
#include "rrc_kernel_interface.h"
#include "selftest_scene.h"

using namespace rrc_ref;
using rrc_ref_test::Scene;

namespace {

// A 3x3 static scene seen by an identity CAMERA: every pixel a hit on its own texel.
Scene static_scene() {
    Scene s(3, 3, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_CAMERA);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    return s;
}

}  // namespace

TEST(Antilag, AHistoryFarOutsideAFlatBlockIsDropped) {
    // Nine 0s (sigma 0) against a history of 1: d = 1/(1 + delta) >= T: c = 0, n_a = 0.
    Scene s = static_scene();
    const int c = s.add_channel(1, 0.8f, RRC_BLEND_AGE_AWARE);
    s.channel_descs[c].antilag = 1;
    FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 1.0f)}, 5));
    for (size_t k = 0; k < s.size(); ++k) {
        EXPECT_EQ(r.mask[k], RRC_MASK_HIT);
        EXPECT_EQ(r.channels[c].out[k], 0.0) << k;  // lambda_eff = 0: the sample alone
        EXPECT_EQ(r.channels[c].age[k], 1) << k;
        EXPECT_EQ(r.channels[c].antilag_age[k], 0) << k;
        EXPECT_NEAR(r.channels[c].antilag_c[k], 0.0, 0.0);
    }
    s.channel_descs[c].antilag = 0;  // without: 0.8 * 1 + 0.2 * 0, age 6
    r = s.run(s.previous({std::vector<float>(s.size(), 1.0f)}, 5));
    EXPECT_NEAR(r.channels[c].out[4], 0.8, 1e-7);
    EXPECT_EQ(r.channels[c].age[4], 6);
}

TEST(Antilag, PartialConfidenceShortensTheAgeAndCapsLambda) {
    // Nine 1s, H = 1.2, gamma_a default 2, T = 0.3: gap 0.2, d = 0.2/(1.2 + delta),
    // c = 2 - 2d/T, n_a = floor(8c) = 7: AGE_AWARE 0.9 -> lambda_eff = 7/8.
    Scene s = static_scene();
    const int a = s.add_channel(1, 0.9f, RRC_BLEND_AGE_AWARE);
    const int f = s.add_channel(1, 0.5f, RRC_BLEND_FIXED);
    for (int c : {a, f}) {
        s.channel_descs[c].antilag = 1;
        s.channel_descs[c].antilag_threshold = 0.3f;
        for (float& v : s.samples[c]) v = 1.0f;
    }
    FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 1.2f), std::vector<float>(s.size(), 1.2f)}, 8));
    const double T = (double)0.3f, H = (double)1.2f;
    const double d = (H - 1.0) / (H + RRC_ANTILAG_DARKNESS), conf = 2.0 - 2.0 * d / T;
    ASSERT_GT(conf * 8, 7.0);
    ASSERT_LT(conf * 8, 8.0);
    EXPECT_NEAR(r.channels[a].antilag_c[4], conf, 1e-12);
    EXPECT_EQ(r.channels[a].antilag_age[4], 7);
    EXPECT_NEAR(r.channels[a].out[4], 7.0 / 8 * H + 1.0 / 8, 1e-12);
    EXPECT_EQ(r.channels[a].age[4], 8);  // n_a + 1
    // FIXED 0.5: lambda_eff = min(0.5, 7/8) = 0.5; the age is still shortened.
    EXPECT_NEAR(r.channels[f].out[4], 0.5 * H + 0.5, 1e-12);
    EXPECT_EQ(r.channels[f].age[4], 8);
    // The default threshold 0.5: d < T/2, c = 1, nothing changes (age 9, lambda_eff min(0.9, 8/9)).
    s.channel_descs[a].antilag_threshold = 0.0f;
    r = s.run(s.previous({std::vector<float>(s.size(), 1.2f), std::vector<float>(s.size(), 1.2f)}, 8));
    EXPECT_EQ(r.channels[a].antilag_c[4], 1.0);
    EXPECT_EQ(r.channels[a].age[4], 9);
    EXPECT_NEAR(r.channels[a].out[4], 8.0 / 9 * H + 1.0 / 9, 1e-12);
}

TEST(Antilag, AHistoryInsideTheBoxIsKept) {
    // Samples 0 / 2 alternating: the centre's block has mu = 8/9, sigma = sqrt(80)/9;
    // a history of 2.5 lies inside mu + 2 sigma = 2.876: gap 0, c = 1.  With
    // gamma_a = 1 (box top 1.883): gap = 2.5 - 1.883, d = gap / (2.5 + sigma + delta).
    Scene s = static_scene();
    const int c = s.add_channel(1, 0.75f, RRC_BLEND_AGE_AWARE);
    s.channel_descs[c].antilag = 1;
    for (size_t k = 0; k < s.size(); ++k) s.samples[c][k] = k % 2 ? 2.0f : 0.0f;
    FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 2.5f)}, 4));
    EXPECT_EQ(r.channels[c].antilag_c[4], 1.0);
    EXPECT_EQ(r.channels[c].age[4], 5);
    s.channel_descs[c].antilag_gamma = 1.0f;
    r = s.run(s.previous({std::vector<float>(s.size(), 2.5f)}, 4));
    const double mu = 8.0 / 9, sigma = std::sqrt(16.0 / 9 - mu * mu);
    const double d = (2.5 - mu - sigma) / (2.5 + sigma + RRC_ANTILAG_DARKNESS);
    const double conf = std::min(1.0, 2.0 - 2.0 * d / 0.5);
    EXPECT_NEAR(r.channels[c].antilag_c[4], conf, 1e-12);
    EXPECT_EQ(r.channels[c].antilag_age[4], (unsigned)std::floor(conf * 4));
}

TEST(Antilag, TheLargestComponentGapDecides) {
    // 4 components: only component 2 left its box; d is its gap.
    Scene s = static_scene();
    const int c = s.add_channel(4, 0.6f, RRC_BLEND_RUNNING_MEAN);
    s.channel_descs[c].antilag = 1;
    for (size_t k = 0; k < s.size(); ++k)
        for (int q = 0; q < 4; ++q) s.samples[c][4 * k + q] = q == 2 ? 0.0f : 1.0f;
    FrameResult r = s.run(s.previous({std::vector<float>(4 * s.size(), 1.0f)}, 10));
    EXPECT_EQ(r.channels[c].antilag_age[4], 0);
    EXPECT_EQ(r.channels[c].age[4], 1);
    for (int q = 0; q < 4; ++q) EXPECT_EQ(r.channels[c].out[4 * 4 + q], q == 2 ? 0.0 : 1.0) << q;
}

TEST(Antilag, OnlyTheBlendCaseIsShortened) {
    Scene s = static_scene();
    const int c = s.add_channel(1, 0.5f, RRC_BLEND_AGE_AWARE);
    s.channel_descs[c].antilag = 1;
    s.samples[c][s.at(0, 0)] = NAN;  // a hit with an invalid sample keeps H and n_prev
    s.nocache[s.at(0, 2)] = 1;        // a miss: the sample, age 1
    s.ctx.use_nocache_mask = 1;
    PreviousFrame prev = s.previous({std::vector<float>(s.size(), 5.0f)}, 3);
    prev.channels[c].age[s.at(2, 2)] = 0;  // an empty history: the sample, age 1
    FrameResult r = s.run(prev);
    EXPECT_EQ(r.channels[c].out[s.at(0, 0)], 5.0);
    EXPECT_EQ(r.channels[c].age[s.at(0, 0)], 3);
    EXPECT_EQ(r.channels[c].age[s.at(0, 2)], 1);
    EXPECT_EQ(r.channels[c].age[s.at(2, 2)], 1);
    for (size_t k : {s.at(0, 0), s.at(0, 2), s.at(2, 2)}) EXPECT_EQ(r.channels[c].antilag_c[k], 1.0) << k;
    EXPECT_EQ(r.channels[c].antilag_c[s.at(1, 1)], 0.0);  // the blend: zeros against 5
    EXPECT_EQ(r.channels[c].age[s.at(1, 1)], 1);
}

TEST(Antilag, AnUnderflowingWeightKeepsTheHistoryAndItsAge) {
    // With confidence, n_a = 0 makes lambda_eff 0 and W' = w: a w of 0 keeps H, n_prev.
    Scene s = static_scene();
    const int c = s.add_channel(1, 0.5f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, RRC_HISTORY_FP32, true);
    s.channel_descs[c].antilag = 1;
    s.confidence[c].assign(s.size(), 0.0f);
    FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 5.0f)}, 3, 1.0f));
    EXPECT_EQ(r.channels[c].antilag_age[4], 0);
    EXPECT_EQ(r.channels[c].out[4], 5.0);
    EXPECT_EQ(r.channels[c].age[4], 3);
    EXPECT_EQ(r.channels[c].weight[4], 0.0);
}
