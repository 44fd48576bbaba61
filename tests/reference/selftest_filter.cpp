// The recursive filter: blend modes, age cap, confidence, fp16 stores, and
// multi-frame accumulation on a static scene.
#include <gtest/gtest.h>

#include <cmath>

#include "filter.h"
#include "selftest_scene.h"

using namespace rrc_ref;
using rrc_ref_test::Scene;

namespace {

ChannelParams channel(rrc_blend blend, double lambda, unsigned cap = 255, bool confidence = false) {
    return {1, false, lambda, blend, RRC_HISTORY_FILTER_BILINEAR, cap, confidence};
}

// out of a hit with H = 1, s = 0: lambda_eff itself.
double lambda_eff_of(const ChannelParams& ch, unsigned n_prev) {
    Sample s;
    Resampled prev;
    prev.h[0] = 1.0;
    prev.age = n_prev;
    return filter_update(ch, PixelCase::hit, s, prev).out[0];
}

// A 4x3 static scene seen by an identity CAMERA with constant depth.
Scene static_scene() {
    Scene s(4, 3, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_CAMERA);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    return s;
}

double sample_value(int frame, size_t pixel) { return std::sin(1.7 * frame + 0.3 * pixel) * 5.0; }

}  // namespace

TEST(Filter, BlendModes) {
    EXPECT_NEAR(lambda_eff_of(channel(RRC_BLEND_FIXED, 0.6), 1), 0.6, 1e-15);
    EXPECT_NEAR(lambda_eff_of(channel(RRC_BLEND_FIXED, 0.6), 100), 0.6, 1e-15);
    EXPECT_NEAR(lambda_eff_of(channel(RRC_BLEND_AGE_AWARE, 0.9), 1), 0.5, 1e-15);
    EXPECT_NEAR(lambda_eff_of(channel(RRC_BLEND_AGE_AWARE, 0.9), 5), 5.0 / 6, 1e-15);
    EXPECT_NEAR(lambda_eff_of(channel(RRC_BLEND_AGE_AWARE, 0.9), 10), 0.9, 1e-15);
    EXPECT_NEAR(lambda_eff_of(channel(RRC_BLEND_RUNNING_MEAN, 0.1), 3), 0.75, 1e-15);
}

TEST(Filter, AgeTable) {
    ChannelParams ch = channel(RRC_BLEND_FIXED, 0.5, 4);
    Sample s;
    s.s[0] = 3.0;
    Resampled prev;
    prev.h[0] = 1.0;
    prev.age = 4;
    EXPECT_EQ(filter_update(ch, PixelCase::hit, s, prev).age, 4u);  // saturated at the cap
    prev.age = 2;
    EXPECT_EQ(filter_update(ch, PixelCase::hit, s, prev).age, 3u);
    prev.age = 0;  // empty history: take the sample
    Update u = filter_update(ch, PixelCase::hit, s, prev);
    EXPECT_EQ(u.out[0], 3.0);
    EXPECT_EQ(u.age, 1u);
    EXPECT_EQ(filter_update(ch, PixelCase::miss, s, prev).age, 1u);
    EXPECT_EQ(filter_update(ch, PixelCase::background, s, prev).age, 0u);
}

TEST(Filter, ConfidenceWeightedMean) {
    ChannelParams ch = channel(RRC_BLEND_FIXED, 0.6, 255, true);
    Sample s;
    s.s[0] = 4.0;
    s.w = 0.25;
    Resampled prev;
    prev.h[0] = 2.0;
    prev.weight = 0.5;
    prev.age = 3;
    Update u = filter_update(ch, PixelCase::hit, s, prev);
    EXPECT_NEAR(u.weight, 0.4, 1e-15);  // 0.6 * 0.5 + 0.4 * 0.25
    EXPECT_NEAR(u.out[0], 2.5, 1e-15);  // (0.6 * 0.5 * 2 + 0.4 * 0.25 * 4) / 0.4
    EXPECT_EQ(u.age, 4u);
    // W' = 0 keeps H and n_prev.
    s.w = 0.0;
    prev.weight = 0.0;
    u = filter_update(ch, PixelCase::hit, s, prev);
    EXPECT_EQ(u.out[0], 2.0);
    EXPECT_EQ(u.age, 3u);
    EXPECT_EQ(u.weight, 0.0);
    // A miss starts W at w.
    s.w = 0.7;
    EXPECT_EQ(filter_update(ch, PixelCase::miss, s, prev).weight, 0.7);
}

TEST(Filter, ConfidenceOfOneEqualsNoConfidence) {
    Scene s = static_scene();
    s.add_channel(4, 0.6f);
    s.add_channel(4, 0.6f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, RRC_HISTORY_FP32, true);
    std::vector<float> history(s.size() * 4);
    for (size_t k = 0; k < history.size(); ++k) {
        history[k] = static_cast<float>(k % 7);
        s.samples[0][k] = s.samples[1][k] = static_cast<float>(k % 5) * 0.5f;
    }
    s.confidence[1][3] = 2.0f;  // clamped to 1
    FrameResult r = s.run(s.previous({history, history}, 2, 1.0f));
    for (size_t k = 0; k < s.size() * 4; ++k) {
        double lambda = 0.6f;
        double expected = lambda * history[k] + (1 - lambda) * s.samples[0][k];
        EXPECT_NEAR(r.channels[0].out[k], expected, 1e-12) << k;
        EXPECT_NEAR(r.channels[1].out[k], expected, 1e-12) << k;
    }
    for (size_t k = 0; k < s.size(); ++k) EXPECT_NEAR(r.channels[1].weight[k], 1.0, 1e-15);
    EXPECT_TRUE(r.channels[0].weight.empty());
}

TEST(Filter, InvalidConfidenceIsAnInvalidSample) {
    Scene s = static_scene();
    s.add_channel(1, 0.5f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, RRC_HISTORY_FP32, true);
    s.confidence[0][5] = NAN;
    s.samples[0][5] = 9.0f;
    FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 3.0f)}, 2, 0.5f));
    EXPECT_EQ(r.mask[5], RRC_MASK_HIT | RRC_MASK_INVALID_SAMPLE);
    EXPECT_EQ(r.channels[0].out[5], 3.0);
    EXPECT_EQ(r.channels[0].weight[5], 0.5);
    EXPECT_EQ(r.channels[0].age[5], 2);
}

TEST(Filter, Fp16HistoryIsRoundedWhenStored) {
    Scene s = static_scene();
    s.add_channel(1, 0.5f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, RRC_HISTORY_FP16);
    s.samples[0][0] = 0.1f;
    s.samples[0][1] = 1e6f;
    FrameResult r = s.run(PreviousFrame{});
    EXPECT_EQ(r.channels[0].exact[0], 0.1f);
    EXPECT_EQ(r.channels[0].out[0], 0.0999755859375);
    EXPECT_EQ(r.channels[0].out[1], 65504.0);
    EXPECT_EQ(r.channels[0].exact[1], 1e6);
}

// CONVENTIONS "fp16 history": above RRC_FP16_MAX_LAMBDA (largest lambda_eff,
// at the capped age) an fp16 request is stored in fp32.
TEST(Filter, Fp16AboveTheLambdaLimitIsStoredInFp32) {
    struct Case {
        float lambda;
        rrc_blend blend;
        uint32_t cap;
        bool fp16;
    };
    const Case cases[] = {
        {0.95f, RRC_BLEND_FIXED, 0, true},        {0.951f, RRC_BLEND_FIXED, 0, false},  {0.999f, RRC_BLEND_AGE_AWARE, 19, true},
        {0.999f, RRC_BLEND_AGE_AWARE, 20, false}, {0.6f, RRC_BLEND_AGE_AWARE, 0, true}, {0.0f, RRC_BLEND_RUNNING_MEAN, 19, true},
        {0.0f, RRC_BLEND_RUNNING_MEAN, 0, false},  // default cap 255: 255/256
    };
    for (const Case& c : cases) {
        Scene s = static_scene();
        s.add_channel(1, c.lambda, c.blend, RRC_HISTORY_FILTER_BILINEAR, RRC_HISTORY_FP16, false, c.cap);
        s.samples[0][0] = 0.1f;
        FrameResult r = s.run(PreviousFrame{});
        EXPECT_EQ(r.channels[0].out[0], c.fp16 ? 0.0999755859375 : (double)0.1f) << c.lambda << " " << c.blend << " " << c.cap;
    }
}

TEST(Filter, RunningMeanIsTheExactMeanOverFrames) {
    Scene s = static_scene();
    s.add_channel(1, 0.0f, RRC_BLEND_RUNNING_MEAN);
    PreviousFrame prev;
    std::vector<double> sum(s.size(), 0.0);
    for (int f = 0; f < 8; ++f) {
        for (size_t k = 0; k < s.size(); ++k) {
            s.samples[0][k] = static_cast<float>(sample_value(f, k));
            sum[k] += s.samples[0][k];
        }
        FrameResult r = s.run(prev);
        for (size_t k = 0; k < s.size(); ++k) {
            EXPECT_EQ(r.mask[k], f == 0 ? 0u : uint32_t(RRC_MASK_HIT));
            EXPECT_NEAR(r.channels[0].out[k], sum[k] / (f + 1), 1e-5) << f << " " << k;
            EXPECT_EQ(r.channels[0].age[k], f + 1);
        }
        prev = as_previous(s.ctx, s.frame, r);
    }
}

TEST(Filter, RunningMeanAtTheCapBecomesFixed) {
    Scene s = static_scene();
    s.add_channel(1, 0.0f, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_BILINEAR, RRC_HISTORY_FP32, false, 3);
    PreviousFrame prev;
    std::vector<double> expected(s.size(), 0.0);
    for (int f = 0; f < 6; ++f) {
        for (size_t k = 0; k < s.size(); ++k) {
            s.samples[0][k] = static_cast<float>(sample_value(f, k));
            double lam = std::min(f, 3) / (std::min(f, 3) + 1.0);  // n_prev saturates at 3
            expected[k] = lam * expected[k] + (1 - lam) * s.samples[0][k];
        }
        FrameResult r = s.run(prev);
        for (size_t k = 0; k < s.size(); ++k) {
            EXPECT_NEAR(r.channels[0].out[k], expected[k], 1e-5) << f << " " << k;
            EXPECT_EQ(r.channels[0].age[k], std::min(f + 1, 3));
        }
        prev = as_previous(s.ctx, s.frame, r);
    }
}
