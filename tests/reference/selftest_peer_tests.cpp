// The peers' validity tests (peer_tests.h) on hand-made frames whose outcome
// follows from each source formula: a plane every test keeps, a depth step
// larger than each threshold, NRD's 1/(N.V) scaling, SVGF's 3x3 fallback and
// FSR2's scattered previous depth at a disocclusion.
#include <gtest/gtest.h>

#include <cmath>

#include "peer_tests.h"

using namespace rrc_ref::peers;

namespace {

constexpr int kW = 16, kH = 16;
const double kTan = std::tan(30.0 * 3.14159265358979323846 / 180.0);

// A fronto-parallel plane at depth z facing the camera (N = V, N.V = 1).
GBuffer plane(double z) {
    GBuffer g;
    g.width = kW;
    g.height = kH;
    g.tan_half_fovy = kTan;
    g.view_z.assign(g.size(), z);
    g.device_z.assign(g.size(), z);
    g.normal.assign(g.size(), glm::dvec3(0, 0, 1));
    g.z_fwidth.assign(g.size(), 0.0);
    g.n_fwidth.assign(g.size(), 0.0);
    g.background.assign(g.size(), 0);
    return g;
}

// Every pixel reprojected by (dx, dy) texels, its expected previous depth z, seen head-on, no parallax.
Reprojection shifted(double dx, double dy, double z) {
    Reprojection r;
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) {
            r.qx.push_back(i + 0.5 + dx);
            r.qy.push_back(j + 0.5 + dy);
            const double ux = r.qx.back() / kW, uy = r.qy.back() / kH;
            r.on_screen.push_back(ux >= 0 && ux <= 1 && uy >= 0 && uy <= 1);
            r.prev_view_z.push_back(z);
            r.view_dir.push_back(glm::dvec3(0, 0, 1));
            r.parallax_px.push_back(0.0);
        }
    return r;
}

size_t at(int i, int j) { return static_cast<size_t>(j) * kW + i; }

int interior_hits(const std::vector<Decision>& d) {
    int n = 0;
    for (int j = 2; j < kH - 2; ++j)
        for (int i = 2; i < kW - 2; ++i) n += d[at(i, j)].hit;
    return n;
}

constexpr int kInterior = (kW - 4) * (kH - 4);

TEST(PeerTests, EveryTestKeepsAnExactPlane) {
    const GBuffer g = plane(10.0);
    const Reprojection r = shifted(0.3, 0.2, 10.0);
    for (PeerTest t : kAllPeerTests) {
        const std::vector<Decision> d = run_peer_test(t, g, r, g);
        EXPECT_EQ(interior_hits(d), kInterior) << peer_name(t);
        // The history weights are normalised and lie on the footprint.
        const Decision& c = d[at(7, 7)];
        double sum = 0.0;
        for (int k = 0; k < c.taps; ++k) sum += c.tap[k].weight;
        EXPECT_NEAR(sum, 1.0, 1e-12) << peer_name(t);
    }
}

TEST(PeerTests, DepthStepsBeyondTheThresholdMiss) {
    const GBuffer cur = plane(10.0);
    const Reprojection r = shifted(0.3, 0.2, 10.0);
    // NRD: 0.01 x frustum (2 tan(30 deg) x 10 = 11.5) = 0.115; SVGF: 10 x 0.01 = 0.1; 1 %: 0.1.
    // A previous surface 0.5 behind fails all three; 0.05 behind passes all three.
    for (PeerTest t : {PeerTest::NRD_REBLUR, PeerTest::NRD_RELAX, PeerTest::SVGF, PeerTest::RELATIVE_1PC}) {
        EXPECT_EQ(interior_hits(run_peer_test(t, cur, r, plane(10.5))), 0) << peer_name(t);
        EXPECT_EQ(interior_hits(run_peer_test(t, cur, r, plane(10.05))), kInterior) << peer_name(t);
    }
    // SVGF compares the current depth with the previous one (not the expected previous depth):
    // a surface moving 0.5 away from the camera misses even though the previous depth is exact.
    EXPECT_EQ(interior_hits(run_peer_test(PeerTest::SVGF, plane(10.0), shifted(0.3, 0.2, 10.5), plane(10.5))), 0);
    EXPECT_EQ(interior_hits(run_peer_test(PeerTest::NRD_REBLUR, plane(10.0), shifted(0.3, 0.2, 10.5), plane(10.5))), kInterior);
}

TEST(PeerTests, NrdGateScalesWithOneOverNDotV) {
    const double F = nrd_frustum_size(kW, kH, kTan, 10.0);
    EXPECT_NEAR(F, 2 * kTan * 10.0, 1e-12);
    EXPECT_NEAR(reblur_threshold(F, 1.0, 0.0), 0.01 * F, 1e-15);
    EXPECT_NEAR(reblur_threshold(F, 0.5, 0.0), 0.01 * F / 0.525, 1e-15);
    EXPECT_NEAR(reblur_threshold(F, 0.0, 0.0), 0.01 * F / 0.05, 1e-15);  // ReBLUR floors N.V at 0.05
    EXPECT_NEAR(relax_threshold(F, 0.5, 0.0), 0.02 * F, 1e-15);
    EXPECT_NEAR(reblur_threshold(F, 0.1, 30.0), 0.01 * F, 1e-15);  // 30 px of parallax: no widening

    // On a frame: a previous surface 0.15 behind misses head-on (0.115) and hits at N.V = 0.5 (0.219).
    GBuffer cur = plane(10.0);
    Reprojection r = shifted(0.3, 0.2, 10.0);
    EXPECT_EQ(interior_hits(run_peer_test(PeerTest::NRD_REBLUR, cur, r, plane(10.15))), 0);
    const glm::dvec3 tilted(std::sqrt(0.75), 0.0, 0.5);
    cur.normal.assign(cur.size(), tilted);
    GBuffer prev = plane(10.15);
    prev.normal.assign(prev.size(), tilted);
    EXPECT_EQ(interior_hits(run_peer_test(PeerTest::NRD_REBLUR, cur, r, prev)), kInterior);
    EXPECT_EQ(interior_hits(run_peer_test(PeerTest::NRD_RELAX, cur, r, prev)), kInterior);
}

TEST(PeerTests, SvgfFallsBackToTheThreeByThreeNeighbourhood) {
    const GBuffer cur = plane(10.0);
    // q = (i + 0.8, j + 0.8): posPrev = i + 0.3, taps (i..i+1, j..j+1); iposPrev = (i, j).
    const Reprojection r = shifted(0.3, 0.3, 10.0);
    GBuffer prev = plane(10.0);
    const int i = 7, j = 7;
    for (int t = 0; t < 4; ++t) prev.view_z[at(i + (t & 1), j + (t >> 1))] = 20.0;
    Decision d = run_peer_test(PeerTest::SVGF, cur, r, prev)[at(i, j)];
    EXPECT_TRUE(d.hit) << "5 of the 3x3 texels around iposPrev pass";
    ASSERT_EQ(d.taps, 5);
    for (int k = 0; k < d.taps; ++k) {
        EXPECT_DOUBLE_EQ(d.tap[k].weight, 0.2);
        EXPECT_NE(prev.view_z[d.tap[k].texel], 20.0);
    }
    for (int y = j - 1; y <= j + 1; ++y)
        for (int x = i - 1; x <= i + 1; ++x) prev.view_z[at(x, y)] = 20.0;
    EXPECT_FALSE(run_peer_test(PeerTest::SVGF, cur, r, prev)[at(i, j)].hit) << "no texel of the 3x3 passes";
}

TEST(PeerTests, Fsr2ClipsWhereANearerSurfaceScattersOntoTheSamePreviousTexel) {
    // A block at depth 5 over columns 8..11 that moved 4 columns right; the wall at depth 10 is static.
    GBuffer cur = plane(10.0);
    Reprojection r = shifted(0.0, 0.0, 10.0);
    for (int j = 0; j < kH; ++j)
        for (int i = 8; i <= 11; ++i) {
            cur.view_z[at(i, j)] = cur.device_z[at(i, j)] = 5.0;
            r.qx[at(i, j)] -= 4.0;
            r.prev_view_z[at(i, j)] = 5.0;
        }
    const std::vector<Decision> d = run_peer_test(PeerTest::FSR2, cur, r, cur);
    for (int i : {4, 5, 6}) EXPECT_FALSE(d[at(i, 8)].hit) << "revealed wall column " << i;
    for (int i : {0, 1, 2, 9, 10, 11, 13, 14}) EXPECT_TRUE(d[at(i, 8)].hit) << "column " << i;
    // Column 7 takes the block's depth and motion (FindNearestDepth's dilation) and keeps history
    // from the previous block: a false hit the dilation makes by design.
    EXPECT_TRUE(d[at(7, 8)].hit);
    EXPECT_EQ(d[at(7, 8)].tap[0].texel % kW, 3u);
    // The term itself: required separation Ksep d tan(fovy/2) W/2, 4x for non-inverted depth.
    const double req = 1.37e-5 * 5.0 * kTan * 8.0;
    EXPECT_NEAR(fsr2_sample_depth_clip(10.0, 5.0, kTan, kW, true), req / 5.0 * 4.0, 1e-15);
    EXPECT_NEAR(fsr2_sample_depth_clip(10.0, 5.0, kTan, kW, false), 4 * req / 5.0 * 4.0, 1e-15);
    // Nearer than the previous: factor 1, ramped by saturate(diff^2) to the base scale 4.
    EXPECT_DOUBLE_EQ(fsr2_sample_depth_clip(5.0, 10.0, kTan, kW, false), 4.0);
}

TEST(PeerTests, RelativeTestIsOnePercentOfTheExpectedDepth) {
    const GBuffer cur = plane(10.0);
    const Reprojection r = shifted(0.3, 0.2, 10.0);
    EXPECT_EQ(interior_hits(run_peer_test(PeerTest::RELATIVE_1PC, cur, r, plane(10.099))), kInterior);
    EXPECT_EQ(interior_hits(run_peer_test(PeerTest::RELATIVE_1PC, cur, r, plane(10.101))), 0);
}

}  // namespace
