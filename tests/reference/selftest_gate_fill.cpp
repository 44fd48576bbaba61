// The deviation gate's weighing of the spatial fill's neighbours in the
// reference (finish.h's spatial_fill with the stored gate state;
// docs/CONVENTIONS.md, "The deviation gate", "With a spatial fill") against
// hand-computed cases: a neighbour further from v_p than kappa sqrt(v_p) is
// left out, one within counts; v_p is varsigma_p - beta_p^2; the first three
// components' mean difference decides; varsigma_p = 0 leaves the fill as it
// is; the fallback is not weighed; a test near the threshold is flagged; and
// run_frame weighs by the state its own pass stored.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "finish.h"
#include "selftest_scene.h"

using namespace rrc_ref;
using rrc_ref_test::Scene;
using rrc_ref_test::stored_beta;
using rrc_ref_test::stored_sq;

namespace {

// A W x 1 row of one RUNNING_MEAN channel with a fill (T, r) and the gate
// (kappa), linear depth 10 everywhere, the gate state per pixel.
struct GateFillRow {
    int W;
    std::vector<rrc_channel_desc> channels;
    rrc_context_desc ctx{};
    std::vector<float> values, fallback, depth;
    std::vector<uint16_t> age;
    std::vector<double> beta, sq, beta_err, sq_err;

    GateFillRow(int w, unsigned components, float kappa, unsigned T = 4, unsigned r = 2, float P = 0.0f) : W(w) {
        rrc_channel_desc d = rrc_host::channel("g", components, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_RUNNING_MEAN);
        d.gate_kappa = kappa;
        d.fill_age = T;
        d.fill_radius = r;
        d.fill_prior = P;
        channels.push_back(d);
        ctx = rrc_host::context_desc(w, 1, channels);
        ctx.depth_mode = RRC_DEPTH_MODE_LINEAR;
        values.assign((size_t)w * components, 0.0f);
        fallback.assign((size_t)w * components, 0.0f);
        depth.assign(w, 10.0f);
        age.assign(w, 8);
        for (auto* v : {&beta, &sq, &beta_err, &sq_err}) v->assign(w, 0.0);
    }
    FillResult run(FillOptions o = {}) {
        ctx.channels = channels.data();
        FillInputs in{values.data(), age.data(), depth.data(), fallback.data()};
        in.gate_beta = beta.data();
        in.gate_sq = sq.data();
        in.gate_beta_err = beta_err.data();
        in.gate_sq_err = sq_err.data();
        return spatial_fill(ctx, 0, in, o);
    }
};

// The centre (2, 0) of a 5-pixel row at age 1 and value 1 among neighbours of
// age 8 (weight min(8, 4) = 4) and values 1.5, 1.125, 1.0625, 0.25: with
// kappa 2 and v_p = 0.01, kappa sqrt(v_p) = 0.2 keeps 1.125 and 1.0625
// (|Delta| 0.125, 0.0625) and leaves 1.5 and 0.25 out (0.5, 0.75).
GateFillRow textured_row() {
    GateFillRow f(5, 1, 2.0f);
    f.values = {1.5f, 1.125f, 1.0f, 1.0625f, 0.25f};
    f.age[2] = 1;
    // v_p = varsigma - beta^2 = 0.0725 - 0.0625 = 0.01 (varsigma alone would keep 1.5: 4 * 0.0725 > 0.25).
    f.beta[2] = 0.25;
    f.sq[2] = 0.0725;
    return f;
}

}  // namespace

TEST(GateFill, ANeighbourBeyondKappaStandardDeviationsIsLeftOut) {
    GateFillRow f = textured_row();
    FillResult r = f.run();
    ASSERT_EQ(r.filled[2], 1);
    EXPECT_EQ(r.neighbours[2], 2);
    EXPECT_EQ(r.gate_excluded[2], 2);
    EXPECT_EQ(r.near_threshold[2], 0);
    EXPECT_EQ(r.gate_near_threshold[2], 0);
    // phi = 3/4: (1 * 1 + 0.75 * 4 * (1.125 + 1.0625)) / (1 + 0.75 * 8) = 7.5625 / 7.
    EXPECT_NEAR(r.shown[2], 7.5625 / 7, 1e-15);
    // Without the weighing (test support), every neighbour: (1 + 3 * 3.9375) / 13.
    FillOptions off;
    off.gate = false;
    EXPECT_NEAR(f.run(off).shown[2], 12.8125 / 13, 1e-15);
    // A larger kappa keeps them all: 3 sqrt(0.01) = 0.3 < 0.5; 8 * 0.1 = 0.8 > 0.75.
    f.channels[0].gate_kappa = 8.0f;
    r = f.run();
    EXPECT_EQ(r.neighbours[2], 4);
    EXPECT_EQ(r.gate_excluded[2], 0);
    EXPECT_NEAR(r.shown[2], 12.8125 / 13, 1e-15);
}

TEST(GateFill, ANeighbourOnTheThresholdCountsAndIsFlagged) {
    // v_p = 1/64, kappa 2: kappa^2 v_p = 1/16 = Delta^2 of 1.25 against 1: counts (<=),
    // within the kernel's fp32 error of the threshold: flagged.
    GateFillRow f(3, 1, 2.0f, 4, 1);
    f.values = {1.25f, 1.0f, 0.5f};
    f.age[1] = 0;
    f.sq[1] = 1.0 / 64;
    FillResult r = f.run();
    EXPECT_EQ(r.neighbours[1], 1);
    EXPECT_EQ(r.gate_excluded[1], 1);  // 0.5: |Delta| 0.5 > 0.25
    EXPECT_EQ(r.gate_near_threshold[1], 1);
    EXPECT_EQ(r.near_threshold[1], 1);
    EXPECT_NEAR(r.shown[1], 1.25, 1e-15);  // age 0: the one neighbour's value
    // Just inside by more than the error: not flagged.
    f.values[0] = 1.24f;
    r = f.run();
    EXPECT_EQ(r.neighbours[1], 1);
    EXPECT_EQ(r.gate_near_threshold[1], 0);
    // The state's own bound counts: varsigma within 0.002 reaches 1.24's Delta^2 / kappa^2.
    f.sq_err[1] = 0.002;
    EXPECT_EQ(f.run().gate_near_threshold[1], 1);
    f.sq_err[1] = 0.0;
    f.beta_err[1] = 0.05;  // beta = 0 +- 0.05: v down to 1/64 - 0.0025, kappa^2 v to 0.0525 < 0.0576
    EXPECT_EQ(f.run().gate_near_threshold[1], 1);
}

TEST(GateFill, TheFirstThreeComponentsMeanDifferenceDecides) {
    // 4 components, v_p = 0.01, kappa 2: kappa sqrt(v_p) = 0.2.  Neighbour 0's
    // colour differences +0.5, -0.25, -0.25 average to 0 and its alpha (100)
    // is not gated: it counts; neighbour 2's +0.25 in each colour is left out.
    GateFillRow f(3, 4, 2.0f, 4, 1);
    f.values = {1.5f, 0.75f, 0.75f, 100.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.25f, 1.25f, 1.25f, 1.0f};
    f.age[1] = 1;
    f.sq[1] = 0.01;
    FillResult r = f.run();
    EXPECT_EQ(r.neighbours[1], 1);
    EXPECT_EQ(r.gate_excluded[1], 1);
    // phi = 3/4: (1 * v_p + 3 * v_0) / 4.
    const double want[4] = {(1.0 + 4.5) / 4, (1.0 + 2.25) / 4, (1.0 + 2.25) / 4, (1.0 + 300.0) / 4};
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(r.shown[4 + k], want[k], 1e-13) << k;
}

TEST(GateFill, WithoutANoiseEstimateTheFillIsUnchanged) {
    // varsigma_p = 0 (a miss, or no blend since): every neighbour counts, whatever beta says.
    GateFillRow f = textured_row();
    f.beta[2] = 0.0;
    f.sq[2] = 0.0;
    FillResult r = f.run();
    EXPECT_EQ(r.neighbours[2], 4);
    EXPECT_EQ(r.gate_excluded[2], 0);
    EXPECT_EQ(r.near_threshold[2], 0);
    EXPECT_NEAR(r.shown[2], 12.8125 / 13, 1e-15);
    // The same as the channel without the gate (which needs no state).
    GateFillRow plain = textured_row();
    plain.channels[0].gate_kappa = 0.0f;
    plain.ctx.channels = plain.channels.data();
    const FillResult p = spatial_fill(plain.ctx, 0, FillInputs{plain.values.data(), plain.age.data(), plain.depth.data(), nullptr});
    for (int i = 0; i < 5; ++i) EXPECT_EQ(r.shown[i], p.shown[i]) << i;
    // varsigma_p = 0 but the kernel's may not be (a bound on it): the test could
    // leave a neighbour out there, so the pixel is flagged and the fill stays.
    f.sq_err[2] = 1e-3;
    r = f.run();
    EXPECT_EQ(r.neighbours[2], 4);
    EXPECT_EQ(r.gate_near_threshold[2], 1);
    // varsigma_p = beta_p^2 > 0: v_p = 0, only a neighbour equal to v_p counts (Delta = 0, not flagged).
    f.sq_err[2] = 0.0;
    f.beta[2] = 0.5;
    f.sq[2] = 0.25;
    f.values[1] = 1.0f;
    r = f.run();
    EXPECT_EQ(r.neighbours[2], 1);
    EXPECT_EQ(r.gate_excluded[2], 3);
    EXPECT_EQ(r.gate_near_threshold[2], 0);
    EXPECT_NEAR(r.shown[2], 1.0, 1e-15);
}

TEST(GateFill, TheFallbackIsNotWeighed) {
    // Every neighbour left out (v_p = 1e-4: kappa sqrt(v_p) = 0.02), a fallback
    // of 3 worth P = 4, far from v_p: (1 * 1 + 0.75 * 4 * 3) / (1 + 0.75 * 4) = 10 / 4.
    GateFillRow f(3, 1, 2.0f, 4, 1, 4.0f);
    f.values = {2.0f, 1.0f, 0.5f};
    f.fallback = {0.0f, 3.0f, 0.0f};
    f.age[1] = 1;
    f.sq[1] = 1e-4;
    FillResult r = f.run();
    EXPECT_EQ(r.neighbours[1], 0);
    EXPECT_EQ(r.gate_excluded[1], 2);
    EXPECT_NEAR(r.shown[1], 2.5, 1e-15);
}

TEST(GateFill, AGatedChannelsFillNeedsTheState) {
    GateFillRow f = textured_row();
    f.ctx.channels = f.channels.data();
    EXPECT_THROW(spatial_fill(f.ctx, 0, FillInputs{f.values.data(), f.age.data(), f.depth.data(), nullptr}), std::invalid_argument);
}

TEST(GateFill, RunFrameWeighsByTheStateItsPassStored) {
    // 3x3, every pixel a hit on its own texel, n_prev = 1 (a = 1/2), the
    // previous state (0, 0), history 1: d = s - 1, beta = d / 2, varsigma =
    // d^2 / 2, so v = d^2 / 4 and kappa 2 gives kappa^2 v = d^2.  AGE_AWARE
    // 0.9 blends at 1/2: out = (1 + s) / 2, age 2 < T = 4.  The centre's
    // sample 1.25 (out 1.125, threshold |Delta| <= 0.25) keeps its neighbours
    // of sample 1 (out 1, Delta -0.125) and leaves out the corner's sample 3
    // (out 2, Delta 0.875).  phi = 1/2, w = 2:
    // (2 * 1.125 + 0.5 * 2 * 7) / (2 + 0.5 * 14) = 9.25 / 9.
    Scene s(3, 3, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_CAMERA);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    const int c = s.add_channel(1, 0.9f, RRC_BLEND_AGE_AWARE);
    s.channel_descs[c].gate_kappa = 2.0f;
    s.channel_descs[c].fill_age = 4;
    s.channel_descs[c].fill_radius = 1;
    s.samples[c].assign(s.size(), 1.0f);
    s.samples[c][4] = 1.25f;
    s.samples[c][0] = 3.0f;
    const FrameResult r = s.run(s.previous({std::vector<float>(s.size(), 1.0f)}, 1));
    const ChannelResult& out = r.channels[c];
    ASSERT_EQ(out.age[4], 2);
    EXPECT_EQ(out.out[4], 1.125);
    EXPECT_EQ(out.out[0], 2.0);
    EXPECT_EQ(out.gate_sq[4], stored_sq(0.03125));
    EXPECT_NEAR(out.shown[4], 9.25 / 9, 1e-15);
    // The corner (v = 1, threshold 2) keeps every neighbour; the edge pixels
    // (d = 0: varsigma = 0) are filled as without the gate.
    const double phi = 0.5;
    EXPECT_NEAR(out.shown[0], (2 * 2.0 + phi * 2 * (2 * 1.0 + 1.125)) / (2 + phi * 2 * 3), 1e-15);
    EXPECT_NEAR(out.shown[1], (2 * 1.0 + phi * 2 * (2.0 + 1.125 + 3 * 1.0)) / (2 + phi * 2 * 5), 1e-15);
}
