// The blur bound of the reference (finish.h, docs/CONVENTIONS.md "The blur
// bound") against hand-computed cases: the fetch's blur b per filter, the age
// cap floor(B / b) and the lambda_eff it caps, with the lag detector, and
// where it applies.
#include <gtest/gtest.h>

#include <cmath>

#include "finish.h"
#include "selftest_scene.h"

using namespace rrc_ref;
using rrc_ref_test::Scene;

namespace {

// A 3x3 static scene seen by an identity CAMERA whose current sample sits jx
// pixels right of the previous one: every pixel a hit at q = i + 0.5 + jx, so
// the fetch's x fraction is jx (y's is 0).
Scene shifted_scene(float jx) {
    Scene s(3, 3, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_CAMERA);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    s.frame.jitter[0] = jx;
    s.frame.prev_jitter[0] = 0.0f;
    return s;
}

ChannelParams params(rrc_history_filter filter, double sigma = 0.5) {
    ChannelParams ch{};
    ch.filter = filter;
    ch.blur_g = sigma * sigma / 2.0;
    return ch;
}

}  // namespace

TEST(BlurBound, TheMomentOfEachFilter) {
    // BILINEAR f(1 - f): (1 - f) f^2 + f (1 - f)^2.
    for (double f : {0.0, 0.1, 0.25, 0.5, 0.8}) EXPECT_NEAR(resampling_blur(params(RRC_HISTORY_FILTER_BILINEAR), f), f * (1 - f), 1e-15) << f;
    // GAUSSIAN sigma 0.5 (g = 1/8), f = 0.3: weights 0.0875, 0.6625, 0.2875, 0.0375 at -1, 0, 1, 2;
    // 0.0875 * 1.69 + 0.6625 * 0.09 + 0.2875 * 0.49 + 0.0375 * 2.89 = 0.46 = 0.21 + sigma^2.
    EXPECT_NEAR(resampling_blur(params(RRC_HISTORY_FILTER_GAUSSIAN), 0.3), 0.46, 1e-15);
    EXPECT_NEAR(resampling_blur(params(RRC_HISTORY_FILTER_GAUSSIAN, 0.8), 0.0), 0.64, 1e-15);
    // NEAREST and CATMULL_ROM: no blur.
    EXPECT_EQ(resampling_blur(params(RRC_HISTORY_FILTER_NEAREST), 0.3), 0.0);
    EXPECT_EQ(resampling_blur(params(RRC_HISTORY_FILTER_CATMULL_ROM), 0.3), 0.0);
}

TEST(BlurBound, TheAgeIsCappedAtBOverB) {
    // f = 0.25: b = 0.1875; B = 1: N = floor(5.33) = 5 < n_prev = 8.
    // AGE_AWARE 0.9: lambda_eff = min(0.9, 8/9) capped to 5/6; age 6.
    Scene s = shifted_scene(0.25f);
    const int a = s.add_channel(1, 0.9f, RRC_BLEND_AGE_AWARE);
    const int f = s.add_channel(1, 0.5f, RRC_BLEND_FIXED);
    for (int c : {a, f}) {
        s.channel_descs[c].blur_bound = 1.0f;
        for (float& v : s.samples[c]) v = 1.0f;
    }
    const std::vector<float> H(s.size(), 2.0f);
    FrameResult r = s.run(s.previous({H, H}, 8));
    for (size_t k = 0; k < s.size(); ++k) {
        ASSERT_EQ(r.mask[k], RRC_MASK_HIT) << k;
        EXPECT_NEAR(r.channels[a].blur_b[k], 0.1875, 1e-9) << k;
        EXPECT_EQ(r.channels[a].blur_age[k], 5) << k;
        EXPECT_EQ(r.channels[a].blur_uncertain[k], 0) << k;
        EXPECT_NEAR(r.channels[a].out[k], 5.0 / 6 * 2.0 + 1.0 / 6, 1e-12) << k;
        EXPECT_EQ(r.channels[a].age[k], 6) << k;
        // FIXED 0.5: min(0.5, 5/6) = 0.5; the age is still the capped one.
        EXPECT_NEAR(r.channels[f].out[k], 0.5 * 2.0 + 0.5, 1e-12) << k;
        EXPECT_EQ(r.channels[f].age[k], 6) << k;
    }
    // B = 2: N = floor(10.67) = 10 >= 8: nothing changes (lambda_eff 8/9, age 9).
    s.channel_descs[a].blur_bound = 2.0f;
    r = s.run(s.previous({H, H}, 8));
    EXPECT_EQ(r.channels[a].blur_age[4], 10);
    EXPECT_NEAR(r.channels[a].out[4], 8.0 / 9 * 2.0 + 1.0 / 9, 1e-12);
    EXPECT_EQ(r.channels[a].age[4], 9);
    // B = 0.1: N = 0: the sample alone.
    s.channel_descs[a].blur_bound = 0.1f;
    r = s.run(s.previous({H, H}, 8));
    EXPECT_EQ(r.channels[a].out[4], 1.0);
    EXPECT_EQ(r.channels[a].age[4], 1);
}

TEST(BlurBound, NoFractionNoCap) {
    // f = 0 on both axes: b = 0, no cap (the static camera without jitter).
    Scene s = shifted_scene(0.0f);
    const int a = s.add_channel(1, 0.9f, RRC_BLEND_AGE_AWARE);
    s.channel_descs[a].blur_bound = 0.01f;
    FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 2.0f)}, 8));
    EXPECT_EQ(r.channels[a].blur_b[4], 0.0);
    EXPECT_EQ(r.channels[a].blur_age[4], RRC_MAX_AGE_CAP);
    EXPECT_EQ(r.channels[a].blur_uncertain[4], 0);
    EXPECT_EQ(r.channels[a].age[4], 9);
}

TEST(BlurBound, AStepOfTheFloorIsUncertain) {
    // f = 0.5: b = 0.25 and B = 1 give N = 4 exactly, on a step of the floor:
    // an fp32 b one ulp larger gives 3, so the age is flagged.
    Scene s = shifted_scene(0.5f);
    const int a = s.add_channel(1, 0.9f, RRC_BLEND_AGE_AWARE);
    s.channel_descs[a].blur_bound = 1.0f;
    FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 2.0f)}, 8));
    EXPECT_EQ(r.channels[a].blur_age[4], 4);
    EXPECT_EQ(r.channels[a].blur_uncertain[4], 1);
    // With n_prev = 3 below both candidates, the age is certain: 4.
    r = s.run(s.previous({std::vector<float>(s.size(), 2.0f)}, 3));
    EXPECT_EQ(r.channels[a].blur_uncertain[4], 0);
    EXPECT_EQ(r.channels[a].age[4], 4);
}

TEST(BlurBound, GaussianAddsItsOwnBlur) {
    // sigma_b 0.5, f = (0.25, 0): b = max(0.1875 + 0.25, 0 + 0.25) = 0.4375;
    // B = 1.5: N = floor(3.43) = 3.  Catmull-Rom and nearest: b = 0, no cap.
    Scene s = shifted_scene(0.25f);
    const int g = s.add_channel(1, 0.9f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_GAUSSIAN);
    const int cr = s.add_channel(1, 0.9f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_CATMULL_ROM);
    const int nn = s.add_channel(1, 0.9f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_NEAREST);
    for (int c : {g, cr, nn}) s.channel_descs[c].blur_bound = 1.5f;
    const std::vector<float> H(s.size(), 2.0f);
    FrameResult r = s.run(s.previous({H, H, H}, 8));
    EXPECT_NEAR(r.channels[g].blur_b[4], 0.4375, 1e-9);
    EXPECT_EQ(r.channels[g].blur_age[4], 3);
    EXPECT_EQ(r.channels[g].age[4], 4);
    EXPECT_NEAR(r.channels[g].out[4], 3.0 / 4 * 2.0, 1e-12);  // samples 0
    for (int c : {cr, nn}) {
        EXPECT_EQ(r.channels[c].blur_b[4], 0.0) << c;
        EXPECT_EQ(r.channels[c].age[4], 9) << c;
    }
}

TEST(BlurBound, TheSmallerOfTheLagDetectorsAgeAndTheCapWins) {
    // The lag detector's case (selftest_antilag.cpp): nine 1s, H = 1.2, T = 0.3, n_prev 8: n_a = 7.
    // f = 0.25: B = 1 caps at 5 (age 6); B = 2 caps at 10, n_a = 7 wins (age 8).
    Scene s = shifted_scene(0.25f);
    const int a = s.add_channel(1, 0.9f, RRC_BLEND_AGE_AWARE);
    s.channel_descs[a].antilag = 1;
    s.channel_descs[a].antilag_threshold = 0.3f;
    for (float& v : s.samples[a]) v = 1.0f;
    const std::vector<float> H(s.size(), 1.2f);
    s.channel_descs[a].blur_bound = 1.0f;
    FrameResult r = s.run(s.previous({H}, 8));
    EXPECT_EQ(r.channels[a].antilag_age[4], 7);
    EXPECT_EQ(r.channels[a].age[4], 6);
    EXPECT_NEAR(r.channels[a].out[4], 5.0 / 6 * (double)1.2f + 1.0 / 6, 1e-12);
    s.channel_descs[a].blur_bound = 2.0f;
    r = s.run(s.previous({H}, 8));
    EXPECT_EQ(r.channels[a].age[4], 8);
    EXPECT_NEAR(r.channels[a].out[4], 7.0 / 8 * (double)1.2f + 1.0 / 8, 1e-12);
}

TEST(BlurBound, OnlyTheBlendCaseIsCapped) {
    Scene s = shifted_scene(0.25f);
    const int c = s.add_channel(1, 0.5f, RRC_BLEND_AGE_AWARE);
    s.channel_descs[c].blur_bound = 0.1f;  // N = 0 wherever it applies
    s.samples[c][s.at(0, 0)] = NAN;       // a hit with an invalid sample keeps H and n_prev
    s.nocache[s.at(0, 2)] = 1;             // a miss: the sample, age 1
    s.ctx.use_nocache_mask = 1;
    PreviousFrame prev = s.previous({std::vector<float>(s.size(), 5.0f)}, 3);
    prev.channels[c].age[s.at(2, 2)] = 0;  // an empty history: the sample, age 1
    FrameResult r = s.run(prev);
    EXPECT_EQ(r.channels[c].out[s.at(0, 0)], 5.0);
    EXPECT_EQ(r.channels[c].age[s.at(0, 0)], 3);
    EXPECT_EQ(r.channels[c].age[s.at(0, 2)], 1);
    EXPECT_EQ(r.channels[c].age[s.at(2, 2)], 1);
    for (size_t k : {s.at(0, 0), s.at(0, 2), s.at(2, 2)}) EXPECT_EQ(r.channels[c].blur_age[k], RRC_MAX_AGE_CAP) << k;
    EXPECT_EQ(r.channels[c].blur_age[s.at(1, 1)], 0);  // the blend: the sample alone
    EXPECT_EQ(r.channels[c].out[s.at(1, 1)], 0.0);
    EXPECT_EQ(r.channels[c].age[s.at(1, 1)], 1);
}
