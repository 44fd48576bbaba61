// The view-dependent history's age cap of the reference (view_lobe.h,
// docs/measurements/PERFORMANCE.md "The view-dependent history (env): the rule,
// measured before building it") against hand-computed cases: the angle between the two view
// directions, the capped age floor(lobe/theta), the lambda_eff it caps, and
// the world position a pixel's depth gives.
#include <gtest/gtest.h>

#include <cmath>

#include "view_lobe.h"

using namespace rrc_ref;

TEST(ViewLobe, ASidewaysStepCapsTheAgeAtFloorOfLobeOverTheta) {
    // P 10 ahead of C; the camera was 1 to the side: theta = atan(1/10) =
    // 0.0996686525; lobe 0.25 -> r = 2.5083 -> n_v = 2 (lambda_eff <= 2/3).
    const double P[3] = {0, 0, 10}, C[3] = {0, 0, 0}, Cp[3] = {1, 0, 0};
    const ViewLobe v = view_lobe_age(0.25, P, C, Cp, 5);
    EXPECT_NEAR(v.theta, 0.0996686524911620, 1e-15);
    EXPECT_NEAR(v.r, 2.50831122676378, 1e-12);
    EXPECT_EQ(v.age, 2u);
    EXPECT_DOUBLE_EQ(view_lobe_lambda(0.8, 5, v.age), 2.0 / 3.0);
    // A younger history than the cap keeps its age and lambda_eff.
    const ViewLobe young = view_lobe_age(0.25, P, C, Cp, 1);
    EXPECT_EQ(young.age, 1u);
    EXPECT_DOUBLE_EQ(view_lobe_lambda(0.5, 1, young.age), 0.5);
}

TEST(ViewLobe, AWideLobeOrAStillViewDirectionCapsNothing) {
    const double P[3] = {0, 0, 10}, C[3] = {0, 0, 0};
    // Moving along the ray to P: the view direction does not turn (theta = 0).
    const double along[3] = {0, 0, -5};
    ViewLobe v = view_lobe_age(0.01, P, C, along, 7);
    EXPECT_EQ(v.theta, 0.0);
    EXPECT_TRUE(std::isinf(v.r));
    EXPECT_EQ(v.age, 7u);
    EXPECT_DOUBLE_EQ(view_lobe_lambda(0.9, 7, v.age), 0.9);
    // theta = atan(1/10), lobe 1 -> r = 10.03 >= n_prev = 7: no cap.
    const double side[3] = {1, 0, 0};
    v = view_lobe_age(1.0, P, C, side, 7);
    EXPECT_EQ(v.age, 7u);
    // The camera on the point: no view direction, no cap.
    v = view_lobe_age(0.01, P, P, side, 7);
    EXPECT_EQ(v.age, 7u);
}

TEST(ViewLobe, ALobeNarrowerThanTheTurnDropsTheHistory) {
    // theta = 45 degrees (P - C = (0,0,1), P - C_prev = (-1,0,1)), lobe 0.5 < pi/4: n_v = 0,
    // lambda_eff = 0 (the sample alone).
    const double P[3] = {0, 0, 1}, C[3] = {0, 0, 0}, Cp[3] = {1, 0, 0};
    const ViewLobe v = view_lobe_age(0.5, P, C, Cp, 9);
    EXPECT_NEAR(v.theta, std::atan(1.0), 1e-15);
    EXPECT_EQ(v.age, 0u);
    EXPECT_EQ(view_lobe_lambda(0.9, 9, v.age), 0.0);
}

TEST(ViewLobe, TheWorldPositionFromDepthInvertsTheViewProjection) {
    // VP = diag(2, 3, 0.5, 1) with translation (0.1, 0.2, 0.25); its inverse is
    // diag(0.5, 1/3, 2, 1) with translation (-0.05, -0.2/3, -0.5).  The point
    // (0.3, -0.4, 1) maps to ndc (0.7, -1.0, 0.75); back again.
    const double inv[16] = {0.5, 0, 0, 0, 0, 1.0 / 3.0, 0, 0, 0, 0, 2, 0, -0.05, -0.2 / 3.0, -0.5, 1};
    double P[3];
    ASSERT_TRUE(view_lobe_world_position(inv, 0.7, -1.0, 0.75, P));
    EXPECT_NEAR(P[0], 0.3, 1e-15);
    EXPECT_NEAR(P[1], -0.4, 1e-15);
    EXPECT_NEAR(P[2], 1.0, 1e-15);
    // A projective row (w = z): the division by X.w.  inverse with row 3 = (0, 0, 1, 0):
    // X = (x, y, z, z) -> P = (x/z, y/z, 1).
    const double proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0};
    ASSERT_TRUE(view_lobe_world_position(proj, 0.5, -0.25, 0.5, P));
    EXPECT_DOUBLE_EQ(P[0], 1.0);
    EXPECT_DOUBLE_EQ(P[1], -0.5);
    EXPECT_DOUBLE_EQ(P[2], 1.0);
    EXPECT_FALSE(view_lobe_world_position(proj, 0.5, -0.25, 0.0, P));  // w = 0
}
