// Age saturation (docs/measurements/STABILITY.md, "Long cases", row "age cap"): with the cap at its type's maximum
// (RRC_MAX_AGE_CAP = 65535, ages are 16-bit) a static 2x2 image runs
// cap + 10 frames in batches; the age must count 1, 2, ... up to 65535 and
// stay there, never wrap to 0, in every channel and blend (checked on every
// 61st frame and on every frame from cap - 6 on).  The
// running mean of alternating 0/1 samples must sit at 0.5 (its lambda_eff
// n/(n+1) approaches 1 in fp32 without breaking).
#include "stability_report.h"
#include "stability_util.h"

#include <cmath>

using namespace rrc_stab;
using rrc_test::channel;

TEST(AgeCap, SaturatesAtTheTypeMaximumWithoutWrapping) {
    const uint32_t W = 2, H = 2, cap = RRC_MAX_AGE_CAP;
    const int frames = (int)cap + 10;
    // Small batches: synchronization validation's cost grows with the square
    // of a command buffer's length (without validation a batch is linear).
    const int chunk = 64;
    std::vector<rrc_channel_desc> channels = {
        channel("fixed", 1, 0.5f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_NEAREST, cap),
        channel("mean", 1, 0.0f, RRC_HISTORY_FP16, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_BILINEAR, cap),
        channel("age_aware", 4, 0.9f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_CATMULL_ROM, cap),
        channel("conf", 1, 0.5f, RRC_HISTORY_FP32, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_NEAREST, cap, 1),
    };
    rrc_test::Context ctx(static_desc(W, H, channels));
    ASSERT_TRUE(ctx);
    uint32_t max_age = 0, wrong = 0;
    float last_mean = 0;
    for (int t0 = 0; t0 < frames; t0 += chunk) {
        const int count = std::min(chunk, frames - t0);
        std::vector<FrameData> batch;
        for (int t = t0; t < t0 + count; ++t) {
            FrameData f = static_frame(W, H, t);
            const float s = (float)(t % 2);
            f.samples = {std::vector<float>(4, s), std::vector<float>(4, s), std::vector<float>(16, s), std::vector<float>(4, s)};
            f.confidence = {{}, {}, {}, std::vector<float>(4, 1.0f)};
            f.read_values = t % 61 == 0 || t + 6 >= (int)cap;  // a sample of frames, and all around the cap
            batch.push_back(std::move(f));
        }
        std::vector<rrc_test::FrameResult> r = run_batch(ctx.get(), ctx.desc(), batch);
        for (int k = 0; k < count; ++k) {
            if (!batch[k].read_values) continue;
            const uint32_t want = std::min<uint32_t>(t0 + k + 1, cap);
            for (size_t c = 0; c < channels.size(); ++c)
                for (uint16_t a : r[k].age[c]) {
                    wrong += a != want;
                    max_age = std::max<uint32_t>(max_age, a);
                }
            for (size_t c = 0; c < channels.size(); ++c)
                for (float v : r[k].values[c]) ASSERT_TRUE(std::isfinite(v)) << "frame " << t0 + k;
        }
        if (batch[count - 1].read_values) last_mean = r[count - 1].values[1][0];
    }
    EXPECT_EQ(wrong, 0u) << "ages must count up to the cap and stay there";
    EXPECT_EQ(max_age, cap);
    EXPECT_NEAR(last_mean, 0.5f, 1e-3f) << "running mean of alternating 0/1 at the cap";
    report("age cap", format("cap %u (the 16-bit maximum), %d frames, 4 channels, batches of %d", cap, frames, chunk),
           "age = min(t + 1, cap) (every 61st frame, every frame from cap - 6), never wraps; running mean |mean - 0.5| < 1e-3",
           format("%u wrong ages, max %u, mean %.6f", wrong, max_age, last_mean));
}
