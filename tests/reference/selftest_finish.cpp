// The 0.4 finishing steps of the reference (finish.h) against hand-computed
// cases: rectification's box and where it applies, the Gaussian filter's
// weights and its 3x3 blur, the spatial fill's formula and its exclusions.
#include <gtest/gtest.h>

#include <cmath>

#include "fetch.h"
#include "finish.h"
#include "selftest_scene.h"

using namespace rrc_ref;
using rrc_ref_test::Scene;

namespace {

// A W x H static scene seen by an identity CAMERA with constant depth: every
// pixel a hit on its own texel centre (q = i + 0.5 exactly).
Scene static_scene(int W = 3, int H = 3) {
    Scene s(W, H, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_CAMERA);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    return s;
}

ChannelParams rectify_channel(unsigned components, double gamma, bool confidence = false) {
    ChannelParams ch{components, false, 0.5, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 255, confidence};
    ch.rectify = true;
    ch.rectify_gamma = gamma;
    return ch;
}

}  // namespace

// ---- Rectification ---------------------------------------------------------

TEST(Rectify, NineEqualSamplesReplaceTheHistoryByTheirMean) {
    Scene s = static_scene();
    const int c = s.add_channel(1, 0.6f);
    s.channel_descs[c].rectify = 1;
    for (float& v : s.samples[c]) v = 2.0f;
    FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 5.0f)}, 3));
    for (size_t k = 0; k < s.size(); ++k) {
        EXPECT_EQ(r.mask[k], RRC_MASK_HIT);
        EXPECT_EQ(r.channels[c].out[k], 2.0) << k;  // H = mu = s: the blend of 2 with 2
        EXPECT_EQ(r.channels[c].age[k], 4);
        EXPECT_EQ(r.channels[c].rectified[k], 1);
    }
    s.channel_descs[c].rectify = 0;  // without: 0.6 * 5 + 0.4 * 2
    r = s.run(s.previous({std::vector<float>(s.size(), 5.0f)}, 3));
    EXPECT_NEAR(r.channels[c].out[4], 3.8, 1e-6);
    EXPECT_EQ(r.channels[c].rectified[4], 0);
}

TEST(Rectify, BoxOfAHandComputedBlock) {
    // Centre (1, 1) of a 3x3 block: eight 0s and a 9: mu = 1, E[s^2] = 9, sigma = sqrt(8).
    ChannelParams ch = rectify_channel(1, 1.0);
    std::vector<float> samples(9, 0.0f);
    samples[0] = 9.0f;
    rrc_channel_input in = rrc_host::channel_input(samples.data());
    RectifyBox b = rectify_box(ch, in, 3, 3, 1, 1);
    EXPECT_EQ(b.taps, 9u);
    EXPECT_DOUBLE_EQ(b.mu[0], 1.0);
    EXPECT_DOUBLE_EQ(b.sigma[0], std::sqrt(8.0));
    EXPECT_DOUBLE_EQ(b.lo[0], 1.0 - std::sqrt(8.0));
    EXPECT_DOUBLE_EQ(b.hi[0], 1.0 + std::sqrt(8.0));
    double h[4] = {10.0}, err[4];
    rectify_history(b, 1, h, err);
    EXPECT_DOUBLE_EQ(h[0], 1.0 + std::sqrt(8.0));
    EXPECT_GT(err[0], 0.0);
    h[0] = 2.0;  // inside: unchanged, no error
    rectify_history(b, 1, h, err);
    EXPECT_EQ(h[0], 2.0);
    EXPECT_EQ(err[0], 0.0);
    h[0] = -5.0;
    rectify_history(b, 1, h, err);
    EXPECT_DOUBLE_EQ(h[0], 1.0 - std::sqrt(8.0));
    // gamma 2.5 widens the box by the same sigma.
    b = rectify_box(rectify_channel(1, 2.5), in, 3, 3, 1, 1);
    EXPECT_DOUBLE_EQ(b.hi[0], 1.0 + 2.5 * std::sqrt(8.0));
}

TEST(Rectify, EdgeTapsAreClampedAndRepeat) {
    // Corner (0, 0) of a 3x3 image: the taps (0,0) x4, (1,0) x2, (0,1) x2, (1,1) x1.
    std::vector<float> samples = {1, 2, 100, 3, 4, 100, 100, 100, 100};
    rrc_channel_input in = rrc_host::channel_input(samples.data());
    RectifyBox b = rectify_box(rectify_channel(1, 1.0), in, 3, 3, 0, 0);
    EXPECT_EQ(b.taps, 9u);
    const double mu = (4 * 1 + 2 * 2 + 2 * 3 + 4) / 9.0, m2 = (4 * 1 + 2 * 4 + 2 * 9 + 16) / 9.0;
    EXPECT_DOUBLE_EQ(b.mu[0], mu);
    EXPECT_NEAR(b.sigma[0], std::sqrt(m2 - mu * mu), 1e-14);
}

TEST(Rectify, InvalidTapsAreLeftOutAndComponentsAreIndependent) {
    ChannelParams ch = rectify_channel(4, 1.0, true);
    std::vector<float> samples(9 * 4), confidence(9, 0.5f);
    for (int p = 0; p < 9; ++p)
        for (int k = 0; k < 4; ++k) samples[4 * p + k] = static_cast<float>(k == 0 ? 3 : k * p);
    samples[4 * 2 + 1] = NAN;  // tap 2 invalid: its other components do not count either
    confidence[6] = INFINITY;  // tap 6 invalid through its confidence
    confidence[7] = 0.0f;      // a zero confidence still counts once (weights do not enter mu, sigma)
    rrc_channel_input in = rrc_host::channel_input(samples.data(), confidence.data());
    RectifyBox b = rectify_box(ch, in, 3, 3, 1, 1);
    EXPECT_EQ(b.taps, 7u);
    EXPECT_EQ(b.mu[0], 3.0);
    EXPECT_EQ(b.sigma[0], 0.0);  // a component whose samples agree: lo = hi = mu
    double sum = 0, sum2 = 0;
    for (int p : {0, 1, 3, 4, 5, 7, 8}) sum += 3 * p, sum2 += 9.0 * p * p;
    EXPECT_NEAR(b.mu[3], sum / 7, 1e-14);
    EXPECT_NEAR(b.sigma[3], std::sqrt(sum2 / 7 - (sum / 7) * (sum / 7)), 1e-12);
}

TEST(Rectify, OnlyTheBlendCaseIsRectified) {
    Scene s = static_scene();
    const int c = s.add_channel(1, 0.5f);
    s.channel_descs[c].rectify = 1;
    for (float& v : s.samples[c]) v = 1.0f;
    s.samples[c][s.at(0, 0)] = NAN;  // a hit with an invalid sample keeps H
    s.depth[s.at(2, 0)] = 1.0f;      // background: the sample
    s.samples[c][s.at(2, 0)] = 4.0f;
    s.nocache[s.at(0, 2)] = 1;  // a miss: the sample
    s.ctx.use_nocache_mask = 1;
    PreviousFrame prev = s.previous({std::vector<float>(s.size(), 5.0f)}, 3);
    prev.channels[c].age[s.at(2, 2)] = 0;  // an empty history: the sample
    FrameResult r = s.run(prev);
    EXPECT_EQ(r.channels[c].out[s.at(0, 0)], 5.0);
    EXPECT_EQ(r.channels[c].out[s.at(2, 0)], 4.0);
    EXPECT_EQ(r.channels[c].out[s.at(0, 2)], 1.0);
    EXPECT_EQ(r.channels[c].out[s.at(2, 2)], 1.0);
    // The blend at the centre: the NaN tap left out, the background's 4 counted like
    // any other sample: m = 8, mu = 11/8, E[s^2] = 23/8, sigma = sqrt(63)/8.
    const double hi = 11.0 / 8 + std::sqrt(63.0) / 8;
    EXPECT_NEAR(r.channels[c].out[s.at(1, 1)], 0.5 * hi + 0.5 * 1.0, 1e-15);
    EXPECT_EQ(r.channels[c].rectified[s.at(1, 1)], 1);
    for (int k : {0, 2, 6, 8}) EXPECT_EQ(r.channels[c].rectified[k], 0) << k;
}

TEST(Rectify, AnUnderflowingWeightKeepsTheResampledHistory) {
    // "Only the blend formula uses the clamped H": W' < 2^-126 keeps H as resampled.
    Scene s = static_scene();
    const int c = s.add_channel(1, 0.5f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, RRC_HISTORY_FP32, true);
    s.channel_descs[c].rectify = 1;
    for (float& v : s.samples[c]) v = 1.0f;
    s.confidence[c].assign(s.size(), 0.0f);
    FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 5.0f)}, 3, 0.0f));
    EXPECT_EQ(r.channels[c].out[4], 5.0);
    EXPECT_EQ(r.channels[c].age[4], 3);
    EXPECT_EQ(r.channels[c].weight[4], 0.0);
    EXPECT_EQ(r.channels[c].rectified[4], 1);  // the box was formed; the case did not use it
}

TEST(Rectify, ConfidenceKeepsItsWeightAndTheClampedHistoryBlends) {
    Scene s = static_scene();
    const int c = s.add_channel(1, 0.5f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, RRC_HISTORY_FP32, true);
    s.channel_descs[c].rectify = 1;
    s.channel_descs[c].rectify_gamma = 2.0f;
    // Samples 0 / 2 alternating: the centre's block (five 0s, four 2s) has mu = 8/9.
    for (size_t k = 0; k < s.size(); ++k) s.samples[c][k] = k % 2 ? 2.0f : 0.0f;
    s.confidence[c].assign(s.size(), 0.25f);
    FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 50.0f)}, 3, 0.75f));
    const double mu = 8.0 / 9, sigma = std::sqrt(16.0 / 9 - mu * mu), h = mu + 2 * sigma;
    const double w = 0.5 * 0.75 + 0.5 * 0.25;
    EXPECT_DOUBLE_EQ(r.channels[c].weight[4], w);  // W resampled as before, not clamped
    EXPECT_NEAR(r.channels[c].out[4], (0.5 * 0.75 * h + 0.5 * 0.25 * 0.0) / w, 1e-12);
}

// ---- The Gaussian history filter ------------------------------------------------

TEST(Gaussian, WeightsSumToOneAndBlurTheBilinearWeights) {
    const double g = 0.5 * 0.5 / 2;
    double w[4];
    gaussian_weights(0.0, g, w);  // t = 0: the blur centred on tap i0
    EXPECT_EQ(w[0], g);
    EXPECT_EQ(w[1], 1 - 2 * g);
    EXPECT_EQ(w[2], g);
    EXPECT_EQ(w[3], 0.0);
    gaussian_weights(1.0, g, w);  // t = 1: centred on i0 + 1
    EXPECT_EQ(w[0], 0.0);
    EXPECT_EQ(w[1], g);
    EXPECT_EQ(w[2], 1 - 2 * g);
    EXPECT_EQ(w[3], g);
    const double sigma_max = RRC_MAX_BLUR_SIGMA;
    for (double gg : {0.0, g, 0.32, sigma_max * sigma_max / 2}) {
        for (double t = 0; t <= 1.0; t += 0.125) {
            gaussian_weights(t, gg, w);
            double sum = 0, mean = 0, var = 0;
            for (int a = 0; a < 4; ++a) {
                EXPECT_GE(w[a], 0.0);
                sum += w[a];
                mean += w[a] * (a - 1);
            }
            for (int a = 0; a < 4; ++a) var += w[a] * (a - 1 - mean) * (a - 1 - mean);
            EXPECT_NEAR(sum, 1.0, 1e-15);
            EXPECT_NEAR(mean, t, 1e-15);                    // the bilinear position
            EXPECT_NEAR(var, 2 * gg + t * (1 - t), 1e-15);  // sigma_b^2 plus the bilinear's own
        }
    }
    gaussian_weights(0.3, 0.0, w);  // g = 0 is the bilinear fetch
    EXPECT_EQ(w[1], 0.7);
    EXPECT_EQ(w[2], 0.3);
}

TEST(Gaussian, AStaticPixelResamplesThrough3x3Blur) {
    const double g = 0.8 * 0.8 / 2;
    std::vector<float> delta(5 * 5, 0.0f);
    delta[2 * 5 + 2] = 1.0f;
    Image img{delta.data(), 5, 5, 1};
    auto at = [&](int i, int j) {
        double v;
        resample(img, RRC_HISTORY_FILTER_GAUSSIAN, i + 0.5, j + 0.5, &v, g);
        return v;
    };
    EXPECT_NEAR(at(2, 2), (1 - 2 * g) * (1 - 2 * g), 1e-15);
    EXPECT_NEAR(at(1, 2), g * (1 - 2 * g), 1e-15);
    EXPECT_NEAR(at(3, 1), g * g, 1e-15);
    EXPECT_EQ(at(0, 2), 0.0);
    EXPECT_EQ(at(4, 4), 0.0);
    // Clamped to the edge: the corner's tap -1 is the corner texel again.
    std::vector<float> corner(5 * 5, 0.0f);
    corner[0] = 1.0f;
    Image ci{corner.data(), 5, 5, 1};
    double v;
    resample(ci, RRC_HISTORY_FILTER_GAUSSIAN, 0.5, 0.5, &v, g);
    EXPECT_NEAR(v, (1 - g) * (1 - g), 1e-15);
    // Half a texel off the centre: the blurred bilinear [g/2, 1/2, 1/2, g/2]-ish mix.
    resample(img, RRC_HISTORY_FILTER_GAUSSIAN, 2.5, 3.0, &v, g);  // fx = 0, fy = 0.5 at i0 = 2
    double wy[4];
    gaussian_weights(0.5, g, wy);
    EXPECT_NEAR(v, (1 - 2 * g) * wy[1], 1e-15);
}

TEST(Gaussian, FrameUsesTheChannelSigmaAndBlursWeights) {
    Scene s(5, 5, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_CAMERA);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    const int a = s.add_channel(1, 0.5f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_GAUSSIAN);  // default sigma 0.5
    const int b = s.add_channel(1, 0.5f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_GAUSSIAN, RRC_HISTORY_FP32, true);
    s.channel_descs[b].blur_sigma = 0.8f;
    std::vector<float> delta(s.size(), 0.0f);
    delta[s.at(2, 2)] = 1.0f;
    PreviousFrame prev = s.previous({delta, delta}, 3, 1.0f);
    prev.channels[b].weight = delta;  // W = the delta too: blurred with the same weights
    for (float& v : s.confidence[b]) v = 1.0f;
    FrameResult r = s.run(prev);
    const double ga = 0.125, gb = (double)0.8f * 0.8f / 2;
    EXPECT_NEAR(r.channels[a].out[s.at(2, 2)], 0.5 * (1 - 2 * ga) * (1 - 2 * ga), 1e-12);
    EXPECT_NEAR(r.channels[a].out[s.at(2, 1)], 0.5 * ga * (1 - 2 * ga), 1e-12);
    const double Wc = (1 - 2 * gb) * (1 - 2 * gb), Wn = 0.5 * Wc + 0.5;
    EXPECT_NEAR(r.channels[b].weight[s.at(2, 2)], Wn, 1e-12);
    EXPECT_NEAR(r.channels[b].out[s.at(2, 2)], 0.5 * Wc * Wc / Wn, 1e-12);  // H and W both the blurred delta
}

// ---- The spatial fill --------------------------------------------------------

namespace {

struct FillCase {
    int W, H;
    rrc_context_desc ctx;
    std::vector<rrc_channel_desc> channels;
    std::vector<float> values, depth, fallback;
    std::vector<uint16_t> age;
    FillCase(int w, int h, unsigned components, unsigned T, unsigned r, float P = 0.0f, rrc_depth_mode mode = RRC_DEPTH_MODE_LINEAR)
        : W(w), H(h) {
        rrc_channel_desc d = rrc_host::channel("f", components, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_RUNNING_MEAN);
        d.fill_age = T;
        d.fill_radius = r;
        d.fill_prior = P;
        d.fill_depth_tolerance = 0.05f;  // the hand-computed cases' tolerance (not the library's default)
        channels.push_back(d);
        ctx = rrc_host::context_desc(w, h, channels);
        ctx.depth_mode = mode;
        values.assign(size() * components, 0.0f);
        fallback.assign(size() * components, 0.0f);
        depth.assign(size(), mode == RRC_DEPTH_MODE_LINEAR ? 10.0f : 0.5f);
        age.assign(size(), 0);
    }
    size_t size() const { return (size_t)W * H; }
    size_t at(int i, int j) const { return (size_t)j * W + i; }
    FillResult run(FillOptions o = {}) {
        ctx.channels = channels.data();
        return spatial_fill(ctx, 0, FillInputs{values.data(), age.data(), depth.data(), fallback.data()}, o);
    }
};

}  // namespace

TEST(Fill, HandComputedWindow) {
    // 3x3, T = 4, r = 1: the centre (age 1, value 10) among eight neighbours
    // of age 6 (weight min(6, 4) = 4) and value 2: phi = 3/4,
    // shown = (1 * 10 + 0.75 * 64) / (1 + 0.75 * 32) = 58 / 25.
    FillCase f(3, 3, 1, 4, 1);
    f.values.assign(9, 2.0f);
    f.age.assign(9, 6);
    f.values[4] = 10.0f;
    f.age[4] = 1;
    FillResult r = f.run();
    EXPECT_EQ(r.filled[4], 1);
    EXPECT_EQ(r.neighbours[4], 8);
    EXPECT_NEAR(r.shown[4], 58.0 / 25, 1e-15);
    for (int k : {0, 1, 2, 3, 5, 6, 7, 8}) {  // n_p >= T: v_p
        EXPECT_EQ(r.filled[k], 0);
        EXPECT_EQ(r.shown[k], 2.0);
    }
    // With a fallback worth P = 4 of value 7: (10 + 0.75 (64 + 28)) / (1 + 0.75 (32 + 4)) = 79 / 28.
    f.channels[0].fill_prior = 4.0f;
    f.fallback[4] = 7.0f;
    r = f.run();
    EXPECT_NEAR(r.shown[4], 79.0 / 28, 1e-15);
    // A non-finite fallback is not used.
    f.fallback[4] = NAN;
    EXPECT_NEAR(f.run().shown[4], 58.0 / 25, 1e-15);
    // Without the fade (test support): (10 + 64) / 33.
    FillOptions nofade;
    nofade.fade = false;
    f.fallback[4] = 7.0f;
    EXPECT_NEAR(f.run(nofade).shown[4], (10.0 + 92) / 37, 1e-15);
}

TEST(Fill, NoNeighbourNoFallbackAndTheFadeEndReturnTheValue) {
    FillCase f(3, 3, 1, 4, 1);
    f.values[4] = 3.0f;
    f.age[4] = 2;  // neighbours all of age 0: none counts
    f.values[0] = 100.0f;
    FillResult r = f.run();
    EXPECT_EQ(r.filled[4], 1);
    EXPECT_EQ(r.neighbours[4], 0);
    EXPECT_EQ(r.shown[4], 3.0);
    EXPECT_EQ(r.shown[0], 3.0);   // age 0: the mean of its one neighbour of age >= 1, the centre
    FillCase one(1, 1, 1, 4, 1);  // age 0, no neighbour, no fallback: denominator 0 -> v_p
    one.values[0] = 5.0f;
    EXPECT_EQ(one.run().shown[0], 5.0);
    f.age.assign(9, 4);  // n_p = T: phi = 0 and not filled
    f.values.assign(9, 1.0f);
    f.values[4] = 3.0f;
    r = f.run();
    EXPECT_EQ(r.filled[4], 0);
    EXPECT_EQ(r.shown[4], 3.0);
    // n_p = T - 1 is filled, and the formula is continuous towards T.
    f.age[4] = 3;
    r = f.run();
    EXPECT_NEAR(r.shown[4], (3.0 * 3 + 0.25 * 32) / (3 + 0.25 * 32), 1e-15);
    // An empty pixel among neighbours shows their weighted mean (phi = 1).
    f.age[4] = 0;
    f.age[0] = 1;
    f.values[0] = 9.0f;
    r = f.run();
    EXPECT_NEAR(r.shown[4], (9.0 + 7 * 4) / (1 + 7 * 4), 1e-15);
}

TEST(Fill, WindowExclusions) {
    FillCase f(5, 5, 1, 8, 2, 0.0f, RRC_DEPTH_MODE_LINEAR);
    f.values.assign(25, 1.0f);
    f.age.assign(25, 8);
    f.age[f.at(2, 2)] = 0;
    f.values[f.at(2, 2)] = 0.0f;
    f.values[f.at(0, 0)] = 50.0f;
    f.depth[f.at(0, 0)] = 1e10f;  // background (the default threshold): skipped
    f.values[f.at(4, 4)] = 50.0f;
    f.depth[f.at(4, 4)] = 10.6f;  // |10.6 - 10| > 0.05 * 10: skipped
    f.values[f.at(4, 0)] = 3.0f;
    f.depth[f.at(4, 0)] = 10.4f;  // within: counts
    FillResult r = f.run();
    EXPECT_EQ(r.neighbours[f.at(2, 2)], 22);  // 24 taps less (0, 0) and (4, 4)
    EXPECT_NEAR(r.shown[f.at(2, 2)], (21 * 8 * 1.0 + 8 * 3.0) / (22 * 8), 1e-14);
    EXPECT_EQ(r.filled[f.at(0, 0)], 0);  // a background pixel is not filled
    EXPECT_EQ(r.shown[f.at(0, 0)], 50.0);
    // The tolerance is relative to the centre's proxy: from 10.4's side the 10s count (0.4 < 0.52).
    f.age[f.at(4, 0)] = 1;
    r = f.run();
    EXPECT_EQ(r.neighbours[f.at(4, 0)], 7);  // x 2..4, y 0..2 less itself and the empty (2, 2); the rest outside
    // Outside taps are skipped, not clamped: the corner (0, 4) at r = 2 sees 8 taps, (2, 2) empty.
    f.age[f.at(0, 4)] = 1;
    r = f.run();
    EXPECT_EQ(r.neighbours[f.at(0, 4)], 7);
    // A tighter tolerance drops (4, 0) from the centre's window.
    f.channels[0].fill_depth_tolerance = 0.01f;
    r = f.run();
    EXPECT_EQ(r.neighbours[f.at(2, 2)], 21);
}

TEST(Fill, DepthProxyOfEachMode) {
    EXPECT_EQ(fill_depth_proxy(RRC_DEPTH_MODE_LINEAR, 7.0), 7.0);
    EXPECT_EQ(fill_depth_proxy(RRC_DEPTH_MODE_STANDARD, 0.75), 4.0);
    EXPECT_EQ(fill_depth_proxy(RRC_DEPTH_MODE_REVERSED, 0.25), 4.0);
    // REVERSED: z = 0.01 and 0.0104 are view distances 1/0.01 and 1/0.0104: 3.8% apart, within 5%.
    FillCase f(2, 1, 1, 4, 1, 0.0f, RRC_DEPTH_MODE_REVERSED);
    f.depth = {0.01f, 0.0104f};
    f.age = {0, 3};
    f.values = {0.0f, 6.0f};
    EXPECT_EQ(f.run().neighbours[0], 1);
    f.depth = {0.01f, 0.0106f};  // 5.7%
    EXPECT_EQ(f.run().neighbours[0], 0);
    f.depth = {0.01f, 1.0f};  // the near plane against a far pixel
    EXPECT_EQ(f.run().neighbours[0], 0);
    // STANDARD: background at z = 1 is never a neighbour nor filled.
    FillCase s(2, 1, 1, 4, 1, 0.0f, RRC_DEPTH_MODE_STANDARD);
    s.depth = {0.9f, 1.0f};
    s.age = {0, 3};
    s.values = {0.0f, 6.0f};
    FillResult r = s.run();
    EXPECT_EQ(r.neighbours[0], 0);
    EXPECT_EQ(r.filled[1], 0);
}

TEST(Fill, RunningMeanFillIsTheMeanOfTheWindowsSamples) {
    // v_p the mean of n_p = 2 samples (2 and 4), neighbours of T = 4 or more samples of mean 6,
    // the fade 1/2: (2 * 3 + 0.5 * 4 * 6) / (2 + 0.5 * 4) = 18 / 4.
    FillCase f(2, 1, 4, 4, 1);
    f.age = {2, 9};
    for (int k = 0; k < 4; ++k) f.values[k] = 3.0f + k, f.values[4 + k] = 6.0f;
    FillResult r = f.run();
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(r.shown[k], (2 * (3.0 + k) + 12) / 4, 1e-15) << k;
    // A neighbour with a non-finite component does not count.
    f.values[5] = INFINITY;
    r = f.run();
    EXPECT_EQ(r.neighbours[0], 0);
    EXPECT_EQ(r.shown[0], 3.0);
}

TEST(Fill, RunFrameShowsTheFillAndKeepsTheHistory) {
    Scene s = static_scene(3, 1);
    const int c = s.add_channel(1, 0.0f, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_BILINEAR, RRC_HISTORY_FP16, false, 16);
    s.channel_descs[c].fill_age = 8;
    s.channel_descs[c].fill_radius = 1;
    s.channel_descs[c].fill_prior = 2.0f;
    s.samples[c] = {1.0f, 0.1f, NAN};
    std::vector<float> fallback = {0.5f, 0.5f, 0.25f};
    s.desc();
    s.inputs[c].fallback = fallback.data();
    FrameResult r = run_frame(s.ctx, PreviousFrame{}, s.frame);  // all misses: ages 1, 1, 0
    ASSERT_EQ(r.channels[c].shown.size(), 3u);
    const double v1 = fp16_round(0.1);
    EXPECT_EQ(r.channels[c].out[1], v1);  // history: the sample alone
    const double phi = 7.0 / 8;
    // Standalone reads the displayed values back in fp32: not rounded to fp16.
    EXPECT_DOUBLE_EQ(r.channels[c].shown[0], (1.0 + phi * (v1 + 2 * 0.5)) / (1 + phi * 3));
    EXPECT_DOUBLE_EQ(r.channels[c].shown[1], (v1 + phi * (1.0 + 2 * 0.5)) / (1 + phi * 3));  // (2, 0) is empty
    EXPECT_DOUBLE_EQ(r.channels[c].shown[2], (0.0 + 1.0 * (v1 + 2 * 0.25)) / (0 + 1.0 * 3));
    // An fp16 output image rounds them.
    const std::vector<float> stored(r.channels[c].out.begin(), r.channels[c].out.end());
    FillOptions fp16_image;
    fp16_image.fp16_output = true;
    FillResult f16 =
        spatial_fill(s.ctx, c, FillInputs{stored.data(), r.channels[c].age.data(), s.depth.data(), fallback.data()}, fp16_image);
    EXPECT_EQ(f16.shown[0], fp16_round(r.channels[c].shown[0]));
    EXPECT_EQ(f16.exact[0], r.channels[c].shown[0]);
    s.inputs[c].fallback = nullptr;
    EXPECT_THROW(run_frame(s.ctx, PreviousFrame{}, s.frame), std::invalid_argument);
}
