// Non-finite samples over many frames (docs/measurements/STABILITY.md): the analytic scene
// (moving camera and object, reversed-Z, PREV_CLIP) at 16x16 with 1% of the
// samples of each signal replaced by NaN, +Inf or -Inf, and 1% of the
// confidences too, through four channels (fp32/fp16, 1/4 components, every
// blend and filter, with and without confidence).  Every frame:
//   - no value, weight or age read back is non-finite (or a weight outside [0, 1]);
//   - RRC_MASK_INVALID_SAMPLE is set exactly on the pixels with an invalid
//     input and stats.invalid_samples counts them.
// Shared by the fast test (300 frames) and the long one (10,000 frames).
#pragma once

#include "stability_report.h"
#include "stability_util.h"
#include "support/scene_frames.h"

#include <cmath>

namespace rrc_stab {

inline void run_nonfinite_samples(int frame_count) {
    const int W = 16, H = 16, kChunk = 100;  // short batches: validation cost grows with their square
    const size_t n = (size_t)W * H;
    rrc_scene::SceneConfig sc = rrc_test::scene_config(W, H, RRC_DEPTH_MODE_REVERSED);
    sc.invalid_fraction = 0.01;
    rrc_scene::Scene scene(sc);
    std::vector<rrc_channel_desc> channels = {
        rrc_test::channel("pcf", 1, 0.6f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR),
        rrc_test::channel("env", 4, 0.8f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_CATMULL_ROM),
        rrc_test::channel("soft", 1, 0.0f, RRC_HISTORY_FP16, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_NEAREST, 16, 1),
        rrc_test::channel("acc", 4, 0.95f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0, 1),
    };
    rrc_test::Context ctx(rrc_test::scene_context_desc(sc, RRC_REPROJECTION_PREV_CLIP, channels));
    ASSERT_TRUE(ctx);
    const float bad[] = {NAN, INFINITY, -INFINITY};
    int64_t invalid_total = 0, hits = 0, values_checked = 0;
    for (int t0 = 0; t0 < frame_count; t0 += kChunk) {
        const int count = std::min(kChunk, frame_count - t0);
        std::vector<FrameData> frames(count);
        std::vector<std::vector<uint8_t>> invalid(count);
        for (int k = 0; k < count; ++k) {
            const int t = t0 + k;
            rrc_scene::Frame sf = scene.render(t);
            FrameData& f = frames[k];
            f.index = t;
            f.depth = sf.depth;
            f.reprojection = sf.prev_clip;
            f.samples = {sf.signal1, sf.signal4, sf.signal1, sf.signal4};
            std::vector<float> conf(n);
            for (size_t p = 0; p < n; ++p) conf[p] = 0.25f + 0.75f * sf.truth1[p];
            f.confidence = {{}, {}, conf, conf};
            for (int c : {2, 3})  // 1% of the confidences non-finite, independently per channel
                for (size_t p = 0; p < n; ++p)
                    if (noise01(11 + c, t, p) < 0.01) f.confidence[c][p] = bad[(size_t)(noise01(13 + c, t, p) * 3)];
            invalid[k].assign(n, 0);
            for (size_t p = 0; p < n; ++p) {
                bool bad_input = !std::isfinite(sf.signal1[p]) || !std::isfinite(f.confidence[2][p]) || !std::isfinite(f.confidence[3][p]);
                for (int q = 0; q < 4; ++q) bad_input = bad_input || !std::isfinite(sf.signal4[4 * p + q]);
                invalid[k][p] = bad_input;
            }
        }
        std::vector<rrc_test::FrameResult> res = run_batch(ctx.get(), ctx.desc(), frames);
        for (int k = 0; k < count; ++k) {
            const rrc_test::FrameResult& r = res[k];
            uint64_t expected = 0;
            for (size_t p = 0; p < n; ++p) {
                expected += invalid[k][p];
                ASSERT_EQ((r.mask[p] & RRC_MASK_INVALID_SAMPLE) != 0, invalid[k][p] != 0) << "frame " << t0 + k << " pixel " << p;
            }
            ASSERT_EQ(r.stats.invalid_samples, expected) << "frame " << t0 + k;
            invalid_total += (int64_t)expected;
            hits += (int64_t)r.stats.hits;
            for (size_t c = 0; c < channels.size(); ++c) {
                for (float v : r.values[c]) ASSERT_TRUE(std::isfinite(v)) << "channel " << c << " frame " << t0 + k;
                for (float w : r.weight[c])
                    ASSERT_TRUE(w >= 0.0f && w <= 1.0f) << "weight " << w << " channel " << c << " frame " << t0 + k;
                values_checked += (int64_t)(r.values[c].size() + r.weight[c].size());
            }
        }
    }
    EXPECT_GT(invalid_total, (int64_t)(0.01 * n * frame_count));  // about 3-4% of the pixels: one of four inputs
    EXPECT_GT(hits, (int64_t)(n * frame_count / 4));              // the run exercises hits, not only misses
    report("non-finite samples (16x16, moving scene, 4 channels)",
           format("%d frames, 1%% of samples and confidences NaN/+Inf/-Inf", frame_count),
           "no non-finite value or weight ever; INVALID_SAMPLE and stats.invalid_samples exact every frame",
           format("%lld invalid pixels flagged and counted, %lld values checked, %lld hits", (long long)invalid_total,
                  (long long)values_checked, (long long)hits));
}

}  // namespace rrc_stab
