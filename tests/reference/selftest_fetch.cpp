// The texel fetches: bilinear, Catmull-Rom (clamped), nearest, and the
// previous-depth fetch (z, or 1/d for LINEAR) with its error bound.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fetch.h"
#include "params.h"
#include "selftest_scene.h"

using namespace rrc_ref;

namespace {

// h(x, y) = 3x + 5y + 1 at texel (x, y), 8x8, one component.
std::vector<float> ramp() {
    std::vector<float> v(64);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) v[y * 8 + x] = 3.0f * x + 5.0f * y + 1.0f;
    return v;
}

}  // namespace

TEST(Fetch, NearestIsFloorClamped) {
    EXPECT_EQ(nearest_index(2.999, 8), 2);
    EXPECT_EQ(nearest_index(3.0, 8), 3);
    EXPECT_EQ(nearest_index(-0.1, 8), 0);
    EXPECT_EQ(nearest_index(8.0, 8), 7);
    EXPECT_EQ(nearest_index(1e30, 8), 7);
}

namespace {

// ramp() (3x + 5y + 1 on 8 x 8) resampled at pixel coordinates (x, y).
double fetch_ramp(rrc_history_filter filter, double x, double y) {
    std::vector<float> v = ramp();
    Image img{v.data(), 8, 8, 1};
    double out = 0;
    resample(img, filter, x, y, &out);
    return out;
}

}  // namespace

TEST(Fetch, BilinearOfARampIsExact) {
    EXPECT_NEAR(fetch_ramp(RRC_HISTORY_FILTER_BILINEAR, 2.3, 4.7), 3 * 1.8 + 5 * 4.2 + 1, 1e-12);  // p = (1.8, 4.2)
    EXPECT_NEAR(fetch_ramp(RRC_HISTORY_FILTER_BILINEAR, 0.2, 4.5), 0 + 5 * 4 + 1, 1e-12);          // left edge: clamped taps
    EXPECT_EQ(fetch_ramp(RRC_HISTORY_FILTER_NEAREST, 2.3, 4.7), 3 * 2 + 5 * 4 + 1);
}

TEST(Fetch, CatmullRomReproducesARamp) {
    EXPECT_NEAR(fetch_ramp(RRC_HISTORY_FILTER_CATMULL_ROM, 3.3, 4.1), 3 * 2.8 + 5 * 3.6 + 1, 1e-12);  // p = (2.8, 3.6)
}

TEST(Fetch, CatmullRomIsClampedToTheBilinearTaps) {
    // Row 0, 1, 1, 1, 1: between texels 1 and 2 the cubic overshoots to 1.0625.
    std::vector<float> v = {0, 1, 1, 1, 1};
    Image img{v.data(), 5, 1, 1};
    double out = 0;
    resample(img, RRC_HISTORY_FILTER_CATMULL_ROM, 2.0, 0.5, &out);  // p = 1.5
    EXPECT_EQ(out, 1.0);
    // Between texels 0 and 1 (t = 0.25) it stays inside and is not clamped:
    // taps (0, 0, 1, 1) clamped at the left edge -> w2 + w3.
    resample(img, RRC_HISTORY_FILTER_CATMULL_ROM, 0.75, 0.5, &out);
    double t = 0.25;
    EXPECT_NEAR(out, 0.5 * (-3 * t * t * t + 4 * t * t + t) + 0.5 * (t * t * t - t * t), 1e-15);
}

TEST(Fetch, LinearDepthInterpolatesReciprocals) {
    rrc_ref_test::Scene s(2, 1, RRC_DEPTH_MODE_LINEAR, RRC_REPROJECTION_PREV_CLIP);
    Params p = resolve(s.ctx);
    std::vector<float> depth = {1.0f, 3.0f};
    DepthFetch f = fetch_depth(p, depth, exact(1.0), exact(0.5), 1.0);  // halfway
    EXPECT_NEAR(f.value.v, 1.5, 1e-15);                                 // 1 / ((1 + 1/3) / 2), not 2
    EXPECT_TRUE(f.no_background.value);
    EXPECT_TRUE(f.no_background.sure);
    // Standard NDC depth interpolates z itself.
    rrc_ref_test::Scene n(2, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_PREV_CLIP);
    std::vector<float> z = {0.25f, 0.75f};
    EXPECT_NEAR(fetch_depth(resolve(n.ctx), z, exact(1.0), exact(0.5), 1.0).value.v, 0.5, 1e-15);
}

TEST(Fetch, BackgroundTapWithZeroWeightStillCounts) {
    rrc_ref_test::Scene s(3, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_PREV_CLIP);
    Params p = resolve(s.ctx);
    std::vector<float> z = {0.5f, 0.5f, 1.0f};
    // q = 1.5: p = 1, f = 0, taps 1 and 2 -> texel 2 (background) is a tap.
    DepthFetch f = fetch_depth(p, z, exact(1.5), exact(0.5), 0.0);
    EXPECT_FALSE(f.no_background.value);
    EXPECT_TRUE(f.no_background.sure);  // error scale 0: no position error
    // With a tiny position error the kernel may use taps 0 and 1: unsure.
    f = fetch_depth(p, z, Bounded{1.5, 1e-7}, exact(0.5), 1.0);
    EXPECT_FALSE(f.no_background.value);
    EXPECT_FALSE(f.no_background.sure);
    f = fetch_depth(p, z, exact(1.4), exact(0.5), 1.0);
    EXPECT_TRUE(f.no_background.value);
}

TEST(Fetch, DepthErrorBoundGrowsWithSlopeAndPositionError) {
    rrc_ref_test::Scene s(2, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_PREV_CLIP);
    Params p = resolve(s.ctx);
    std::vector<float> flat = {0.5f, 0.5f}, steep = {0.25f, 0.75f};
    double e_flat = fetch_depth(p, flat, Bounded{1.0, 1e-6}, exact(0.5), 1.0).value.err;
    double e_steep = fetch_depth(p, steep, Bounded{1.0, 1e-6}, exact(0.5), 1.0).value.err;
    EXPECT_LE(e_flat, 8 * 0x1p-24 * 0.5);  // rounding only
    // + step 0.5 times the position error (q's, plus the rounding of p = q - 0.5).
    EXPECT_NEAR(e_steep - e_flat, 0.5 * (1e-6 + 0.5 * 0x1p-24), 1e-15);
}
