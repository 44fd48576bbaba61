// The fp16 stall on the kernel itself, where it is cheap to see: a constant
// signal s = 1.5 after a first sample of 1.0, 2,000 frames on a 4x4 static
// image.  An fp16 history rounded to nearest moves only while
// (1 - λ)|s - H| >= ulp(H)/2, so it stops short of s by about
// ulp(H)/(2(1 - λ)) (2^-11/0.05 ≈ 9.8e-3 at λ = 0.95, where fp16 is kept);
// the same request above RRC_FP16_MAX_LAMBDA is stored in fp32 and converges.
#include "stability_report.h"
#include "stability_util.h"

#include <cmath>

using namespace rrc_stab;
using rrc_test::channel;

namespace {

constexpr int kW = 4, kH = 4, kFrames = 2000;
constexpr float kStart = 1.0f, kTarget = 1.5f;

TEST(Fp16Stall, StallsWhereTheoryPredictsAndPromotionRemovesIt) {
    std::vector<rrc_channel_desc> channels = {
        channel("fp16_095", 1, 0.95f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_NEAREST),
        channel("fp32_095", 1, 0.95f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_NEAREST),
        channel("fp16_099", 1, 0.99f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_NEAREST),
        channel("fp16_mean", 1, 0.0f, RRC_HISTORY_FP16, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_NEAREST),  // cap 255
    };
    rrc_test::Context ctx(static_desc(kW, kH, channels));
    ASSERT_TRUE(ctx);
    std::vector<FrameData> frames;
    for (int t = 0; t < kFrames; ++t) {
        FrameData f = static_frame(kW, kH, t);
        f.samples.assign(channels.size(), std::vector<float>(kW * kH, t == 0 ? kStart : kTarget));
        f.read_values = t >= kFrames - 100;
        frames.push_back(std::move(f));
    }
    std::vector<rrc_test::FrameResult> res = run_batch(ctx.get(), ctx.desc(), frames);
    ASSERT_EQ(res.size(), (size_t)kFrames);
    const rrc_test::FrameResult& last = res.back();
    const rrc_test::FrameResult& earlier = res[kFrames - 100];

    // fp16 at λ = 0.95: stuck for the last 100 frames, short of s by the dead zone.
    const float h = last.values[0][0];
    const double ulp = std::ldexp(1.0, std::ilogb(h) - 10);
    const double gap = kTarget - h;
    const double dead_zone = ulp / (2.0 * (1.0 - 0.95));
    EXPECT_EQ(earlier.values[0], last.values[0]) << "the fp16 history should have stopped moving";
    EXPECT_GT(gap, 0.5 * dead_zone) << "stalled value " << h;
    EXPECT_LE(gap, dead_zone + ulp) << "stalled value " << h;
    // Each step left would be under half an ulp (the store rounds it away).
    EXPECT_LT((1.0 - 0.95f) * gap, 0.5 * ulp + 1e-9);
    // fp32 at the same λ converges (0.95^2000 is nothing).
    EXPECT_NEAR(last.values[1][0], kTarget, 1e-6);
    // Above RRC_FP16_MAX_LAMBDA (λ = 0.99, and a running mean capped at 255)
    // the fp16 request is fp32: both converge where fp16 would stall by
    // 2^-11/0.01 ≈ 4.9e-2 and 2^-11·256 = 0.125.
    EXPECT_NEAR(last.values[2][0], kTarget, 1e-5);
    EXPECT_NEAR(last.values[3][0], kTarget, 1e-4);
    for (int c = 0; c < 4; ++c)
        for (size_t p = 1; p < last.values[c].size(); ++p) EXPECT_EQ(last.values[c][p], last.values[c][0]) << "channel " << c;

    report("fp16 stall (kernel, constant s: 1.0 then 1.5, 2,000 frames)", "λ=0.95 fp16 (kept)",
           "stalls: gap within (0.5, 1]·ulp/(2(1-λ)) + ulp", format("gap %.4g, dead zone ulp/(2(1-λ)) = %.4g", gap, dead_zone));
    report("fp16 stall (kernel, constant s: 1.0 then 1.5, 2,000 frames)", "λ=0.99 fp16 requested (promoted)", "|H - s| < 1e-5",
           format("|H - s| = %.2g (fp16 would stall at ~4.9e-2)", std::fabs(last.values[2][0] - kTarget)));
    report("fp16 stall (kernel, constant s: 1.0 then 1.5, 2,000 frames)", "RUNNING_MEAN cap 255 fp16 requested (promoted)",
           "|H - s| < 1e-4", format("|H - s| = %.2g (fp16 would stall at ~0.12)", std::fabs(last.values[3][0] - kTarget)));
}

}  // namespace
