// CAMERA reprojection against an independent ray-cast of an analytic plane:
// the reference's matrix path (NDC modes, and LINEAR's ray point with clip
// w = d) must land where the ray-cast says, and hit.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "selftest_scene.h"

using rrc_ref::FrameResult;
using rrc_ref_test::Scene;

namespace {

constexpr int kW = 32, kH = 24;
const glm::dvec3 kNormal = glm::normalize(glm::dvec3(0.2, 0.1, 1.0));
constexpr double kPlane = -8.0;  // n . X = kPlane: a tilted wall about 8 units ahead

glm::dmat4 perspective(rrc_depth_mode mode) {
    double fovy = glm::radians(60.0), aspect = double(kW) / kH, n = 0.5, f = 50.0;
    glm::dmat4 p;
    if (mode == RRC_DEPTH_MODE_REVERSED) {  // reversed, infinite far: z_ndc = n / d
        double t = 1.0 / std::tan(fovy / 2);
        p = glm::dmat4(0.0);
        p[0][0] = t / aspect;
        p[1][1] = t;
        p[2][3] = -1.0;
        p[3][2] = n;
    } else {
        p = glm::perspectiveRH_ZO(fovy, aspect, n, f);
    }
    p[1][1] *= -1.0;  // Vulkan: y down
    return p;
}

// The world point of the plane seen at uv through view-projection vp.
glm::dvec3 cast(const glm::dmat4& vp, glm::dvec2 uv) {
    glm::dmat4 inv = glm::inverse(vp);
    glm::dvec2 ndc = uv * 2.0 - 1.0;
    // Two points of the ray at finite depth in every mode (reversed-infinite maps z = 0 to infinity).
    glm::dvec4 a = inv * glm::dvec4(ndc, 0.25, 1.0), b = inv * glm::dvec4(ndc, 0.75, 1.0);
    glm::dvec3 pa = glm::dvec3(a) / a.w, pb = glm::dvec3(b) / b.w;
    double t = (kPlane - glm::dot(kNormal, pa)) / glm::dot(kNormal, pb - pa);
    return pa + t * (pb - pa);
}

// Depth of world point x in the mode (NDC z, or clip w).
double depth_of(const glm::dmat4& vp, glm::dvec3 x, rrc_depth_mode mode) {
    glm::dvec4 c = vp * glm::dvec4(x, 1.0);
    return mode == RRC_DEPTH_MODE_LINEAR ? c.w : c.z / c.w;
}

struct CameraCase {
    Scene s{kW, kH, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_CAMERA};
    glm::dmat4 vp, vp_prev;
    rrc_ref::PreviousFrame prev;

    CameraCase(rrc_depth_mode mode, double yaw_degrees) {
        s.ctx.depth_mode = mode;
        s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
        s.add_channel(1, 0.5f);
        glm::dmat4 proj = perspective(mode);
        glm::dmat4 view_prev = glm::rotate(glm::dmat4(1.0), glm::radians(yaw_degrees), {0, 1, 0});
        view_prev = glm::translate(view_prev, glm::dvec3(-0.05, 0.02, 0.0));
        vp = proj;
        vp_prev = proj * view_prev;
        for (int k = 0; k < 16; ++k) {
            s.frame.view_proj[k] = (&vp[0][0])[k];
            s.frame.prev_view_proj[k] = (&vp_prev[0][0])[k];
        }
        prev = s.previous({std::vector<float>(s.size(), 1.0f)}, 1);
        for (int j = 0; j < kH; ++j)
            for (int i = 0; i < kW; ++i) {
                glm::dvec2 uv((i + 0.5) / kW, (j + 0.5) / kH);
                s.depth[s.at(i, j)] = static_cast<float>(depth_of(vp, cast(vp, uv), mode));
                prev.depth[s.at(i, j)] = static_cast<float>(depth_of(vp_prev, cast(vp_prev, uv), mode));
            }
    }

    // Checks uv_prev and e against the ray-cast, and that interior pixels hit.
    void check(const FrameResult& r, double diff_tolerance) {
        int interior = 0, hits = 0;
        for (int j = 0; j < kH; ++j)
            for (int i = 0; i < kW; ++i) {
                size_t k = s.at(i, j);
                glm::dvec3 x = cast(vp, {(i + 0.5) / kW, (j + 0.5) / kH});
                glm::dvec4 c = vp_prev * glm::dvec4(x, 1.0);
                // Current depth went through float: allow its rounding's effect.
                EXPECT_NEAR(r.uv_prev_x[k], (c.x / c.w + 1) / 2, 1e-5) << i << "," << j;
                EXPECT_NEAR(r.uv_prev_y[k], (c.y / c.w + 1) / 2, 1e-5) << i << "," << j;
                EXPECT_NEAR(r.expected[k], depth_of(vp_prev, x, s.ctx.depth_mode), 1e-5 * std::fabs(r.expected[k]));
                bool inside = r.uv_prev_x[k] > 2.0 / kW && r.uv_prev_x[k] < 1 - 2.0 / kW && r.uv_prev_y[k] > 2.0 / kH &&
                              r.uv_prev_y[k] < 1 - 2.0 / kH;
                if (!inside) continue;
                ++interior;
                hits += r.mask[k] == RRC_MASK_HIT;
                EXPECT_LE(std::fabs(r.diff[k]), diff_tolerance) << i << "," << j;
            }
        EXPECT_GT(interior, kW * kH / 2);
        EXPECT_EQ(hits, interior);
    }
};

}  // namespace

TEST(Camera, StandardDepthRotatingCamera) {
    CameraCase c(RRC_DEPTH_MODE_STANDARD, 3.0);
    c.check(c.s.run(c.prev), 1e-6);  // z is affine on the plane: bilinear is exact
}

TEST(Camera, ReversedInfiniteDepthRotatingCamera) {
    CameraCase c(RRC_DEPTH_MODE_REVERSED, -2.0);
    c.check(c.s.run(c.prev), 1e-6);
}

TEST(Camera, LinearDepthUsesTheRayPointWithClipWEqualToDepth) {
    CameraCase c(RRC_DEPTH_MODE_LINEAR, 3.0);
    FrameResult r = c.s.run(c.prev);
    c.check(r, 1e-5);  // 1/d is affine on the plane: the fetch is exact up to float depth
}

TEST(Camera, PointsBehindThePreviousCameraMiss) {
    CameraCase c(RRC_DEPTH_MODE_LINEAR, 180.0);  // previous camera looks the other way
    FrameResult r = c.s.run(c.prev);
    EXPECT_EQ(r.stats.hits, 0u);
    for (size_t k = 0; k < c.s.size(); ++k) EXPECT_LT(r.expected[k], 0.0);  // clip w < 0
}
