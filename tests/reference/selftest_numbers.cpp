// fp16 rounding, fp32 ulp and the epsilon rules, against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rrc_reference.h"
#include "selftest_scene.h"

using rrc_ref::epsilon_for;
using rrc_ref::fp16_round;
using rrc_ref::ulp_fp32;

TEST(Fp16Round, ExactValuesStay) {
    EXPECT_EQ(fp16_round(1.0), 1.0);
    EXPECT_EQ(fp16_round(-2.5), -2.5);
    EXPECT_EQ(fp16_round(65504.0), 65504.0);
    EXPECT_EQ(fp16_round(0x1p-24), 0x1p-24);  // smallest subnormal half
    EXPECT_EQ(fp16_round(0.0), 0.0);
}

TEST(Fp16Round, ClampsToMaxHalf) {
    EXPECT_EQ(fp16_round(65519.0), 65504.0);
    EXPECT_EQ(fp16_round(65520.0), 65504.0);  // would round to inf without the clamp
    EXPECT_EQ(fp16_round(1e30), 65504.0);
    EXPECT_EQ(fp16_round(-70000.0), -65504.0);
    EXPECT_EQ(fp16_round(INFINITY), 65504.0);
}

TEST(Fp16Round, TiesToEven) {
    EXPECT_EQ(fp16_round(1.0 + 0x1p-11), 1.0);               // 1 | 1+2^-10: even is 1
    EXPECT_EQ(fp16_round(1.0 + 3 * 0x1p-11), 1.0 + 0x1p-9);  // odd 1+2^-10 loses
    EXPECT_EQ(fp16_round(2049.0), 2048.0);
    EXPECT_EQ(fp16_round(2051.0), 2052.0);
    EXPECT_EQ(fp16_round(1.5 * 0x1p-24), 0x1p-23);  // subnormal tie, up to even
    EXPECT_EQ(fp16_round(0.5 * 0x1p-24), 0.0);      // subnormal tie, down to 0
    EXPECT_EQ(fp16_round(2.5 * 0x1p-24), 2 * 0x1p-24);
    EXPECT_EQ(fp16_round(-(1.0 + 0x1p-11)), -1.0);
}

TEST(Fp16Round, NearestOffTies) {
    EXPECT_EQ(fp16_round(0.1), 0.0999755859375);  // 0x2E66
    EXPECT_EQ(fp16_round(1.0 + 0x1p-11 + 0x1p-30), 1.0 + 0x1p-10);
    EXPECT_EQ(fp16_round(0.75 * 0x1p-24), 0x1p-24);
    EXPECT_EQ(fp16_round(0x1p-14 - 0x1p-26), 0x1p-14);  // rounds up into the normal range
}

#ifdef __FLT16_MAX__
// The compiler's float -> _Float16 conversion rounds to nearest even too.
TEST(Fp16Round, AgreesWithCompilerHalfOnRandomFloats) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<uint32_t> bits;
    int checked = 0;
    for (int k = 0; k < 200000; ++k) {
        uint32_t b = bits(rng);
        float f;
        std::memcpy(&f, &b, sizeof f);
        if (!std::isfinite(f) || std::fabs(f) >= 65504.0f) continue;
        EXPECT_EQ(fp16_round(f), static_cast<double>(static_cast<_Float16>(f))) << f;
        ++checked;
    }
    EXPECT_GT(checked, 1000);
}
#endif

TEST(UlpFp32, Binades) {
    EXPECT_EQ(ulp_fp32(0.5), 0x1p-24);
    EXPECT_EQ(ulp_fp32(0.75), 0x1p-24);
    EXPECT_EQ(ulp_fp32(1.0), 0x1p-23);
    EXPECT_EQ(ulp_fp32(-3.0), 0x1p-22);
    EXPECT_EQ(ulp_fp32(0.0), 0x1p-149);
    EXPECT_EQ(ulp_fp32(1e-40), 0x1p-149);         // fp32 denormal
    EXPECT_EQ(ulp_fp32(1.0 - 0x1p-30), 0x1p-23);  // rounds to 1.0f first
}

TEST(Epsilon, Float32DefaultScaleIsFourUlp) {
    rrc_ref_test::Scene s(1, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_PREV_CLIP);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_FLOAT32;
    EXPECT_EQ(epsilon_for(s.ctx, 0.5), 4 * 0x1p-24);
    EXPECT_EQ(epsilon_for(s.ctx, 0.0), 4 * 0x1p-149);
    s.ctx.epsilon_scale = 2.0f;
    EXPECT_EQ(epsilon_for(s.ctx, 0.5), 2 * 0x1p-24);
}

TEST(Epsilon, UnormAndAbsolute) {
    rrc_ref_test::Scene s(1, 1, RRC_DEPTH_MODE_REVERSED, RRC_REPROJECTION_CAMERA);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    EXPECT_EQ(epsilon_for(s.ctx, 0.3), 1.0 / 65535.0);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM24;
    s.ctx.epsilon_scale = 2.0f;
    EXPECT_EQ(epsilon_for(s.ctx, 0.3), 2.0 / 16777215.0);
    s.ctx.epsilon = 0.25f;
    EXPECT_EQ(epsilon_for(s.ctx, 0.3), 0.25);
}

TEST(Epsilon, RelativeForLinearAndPlainMotion) {
    rrc_ref_test::Scene s(1, 1, RRC_DEPTH_MODE_LINEAR, RRC_REPROJECTION_PREV_CLIP);
    s.ctx.epsilon = 0.25f;  // absolute epsilon is for NDC tests only
    EXPECT_DOUBLE_EQ(epsilon_for(s.ctx, 10.0), 0.1);
    s.ctx.tau = 0.5f;
    EXPECT_DOUBLE_EQ(epsilon_for(s.ctx, 10.0), 5.0);
    rrc_ref_test::Scene m(1, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_MOTION);
    EXPECT_DOUBLE_EQ(epsilon_for(m.ctx, 20.0), 0.2);  // linearised NDC depth
    rrc_ref_test::Scene md(1, 1, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_MOTION_DEPTH);
    EXPECT_EQ(epsilon_for(md.ctx, 0.5), 4 * 0x1p-24);  // MOTION_DEPTH: the normal test
}
