// Reset, resolution change and skipped frame indices (docs/measurements/STABILITY.md).
//  - reset: every pixel a miss on that frame, every channel stores exactly
//    its sample (confidence weight = w), age 1: nothing from before survives;
//    inside one batch as well as alone.
//  - resolution change: a context has one size, so a new size is a new
//    context; its first frame is all misses, whatever the old one held.
//  - skipped indices: frame_index only drives refresh clocks; reprojection is
//    against the last frame submitted.  The same frames with indices
//    0,1,2,... or 0,1,7,1000,2^40,... give bit-identical results, and a
//    moving scene submitted with gaps (each frame rendered against the last
//    one submitted) hits with zero false hits.
#include "scenes/false_hits.h"
#include "stability_report.h"
#include "stability_util.h"
#include "support/scene_frames.h"

#include <cmath>

using namespace rrc_stab;
using rrc_test::channel;

namespace {

std::vector<rrc_channel_desc> two_channels() {
    return {channel("conf", 1, 0.8f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0, 1),
            channel("col", 4, 0.6f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_CATMULL_ROM)};
}

FrameData frame_with(uint32_t w, uint32_t h, int t, uint32_t reset) {
    FrameData f = static_frame(w, h, t);
    f.reset = reset;
    const size_t n = (size_t)w * h;
    std::vector<float> s1(n), s4(4 * n), conf(n);
    for (size_t p = 0; p < n; ++p) {
        s1[p] = (float)noise01(5, t, p);
        conf[p] = 0.25f + 0.5f * (float)noise01(6, t, p);
        for (int q = 0; q < 4; ++q) s4[4 * p + q] = 100.0f + (float)noise01(7, t, 4 * p + q);
    }
    f.samples = {s1, s4};
    f.confidence = {conf, {}};
    return f;
}

// A frame after a reset (or the first of a context) holds exactly its inputs.
void expect_fresh(const FrameData& f, const rrc_test::FrameResult& r, const char* what) {
    EXPECT_EQ(r.stats.hits, 0u) << what;
    EXPECT_EQ(r.values[0], f.samples[0]) << what;
    EXPECT_EQ(r.weight[0], f.confidence[0]) << what;
    for (size_t i = 0; i < f.samples[1].size(); ++i)  // fp16 history: the sample rounded to nearest
        EXPECT_NEAR(r.values[1][i], f.samples[1][i], std::ldexp(1.0, std::ilogb(f.samples[1][i]) - 11)) << what;
    EXPECT_EQ(r.age[0], std::vector<uint16_t>(r.age[0].size(), 1)) << what;
    EXPECT_EQ(r.age[1], std::vector<uint16_t>(r.age[1].size(), 1)) << what;
}

TEST(Reset, EveryPixelMissesAndNothingSurvives) {
    const uint32_t W = 8, H = 8;
    const auto channels = two_channels();
    rrc_test::Context ctx(static_desc(W, H, channels));
    ASSERT_TRUE(ctx);
    // One batch: frames 0..4, a reset at 5, frames 6..7; then a lone reset.
    std::vector<FrameData> frames;
    for (int t = 0; t < 8; ++t) frames.push_back(frame_with(W, H, t, t == 5));
    std::vector<rrc_test::FrameResult> r = run_batch(ctx.get(), ctx.desc(), frames);
    EXPECT_EQ(r[4].stats.hits, (uint64_t)W * H);
    EXPECT_EQ(r[4].age[0][0], 5);
    expect_fresh(frames[5], r[5], "reset inside a batch");
    EXPECT_EQ(r[6].stats.hits, (uint64_t)W * H);
    EXPECT_EQ(r[6].age[0], std::vector<uint16_t>(W * H, 2));
    FrameData lone = frame_with(W, H, 8, 1);
    expect_fresh(lone, run_batch(ctx.get(), ctx.desc(), {lone})[0], "reset alone");
    report("reset and resolution change (8x8, 2 channels)", "reset inside a batch and alone", "0 hits; values = s, weight = w, age 1",
           format("hits %llu; exact", (unsigned long long)r[5].stats.hits));
}

TEST(Reset, NewResolutionStartsEmpty) {
    const auto channels = two_channels();
    {
        rrc_test::Context old(static_desc(8, 8, channels));
        ASSERT_TRUE(old);
        std::vector<FrameData> frames;
        for (int t = 0; t < 4; ++t) frames.push_back(frame_with(8, 8, t, 0));
        EXPECT_EQ(run_batch(old.get(), old.desc(), frames).back().stats.hits, 64u);
    }
    for (auto size : {std::pair<uint32_t, uint32_t>{16, 8}, {8, 8}, {3, 5}}) {
        rrc_test::Context ctx(static_desc(size.first, size.second, channels));
        ASSERT_TRUE(ctx);
        FrameData f = frame_with(size.first, size.second, 4, 0);
        expect_fresh(f, run_batch(ctx.get(), ctx.desc(), {f})[0], "first frame after a resolution change");
    }
    report("reset and resolution change (8x8, 2 channels)", "new context at 16x8, 8x8, 3x5 after an 8x8 one",
           "first frame: 0 hits; values = s, weight = w, age 1", "exact");
}

// Frame indices are not used for reprojection: bit-identical results.
TEST(SkippedIndices, OnlyTheOrderOfSubmissionMatters) {
    rrc_scene::SceneConfig sc;
    sc.width = 48;
    sc.height = 32;
    sc.depth_mode = RRC_DEPTH_MODE_REVERSED;
    sc.jitter = true;
    rrc_scene::Scene scene(sc);
    std::vector<rrc_channel_desc> channels = {channel("pcf", 1, 0.6f), channel("env", 4, 0.6f, RRC_HISTORY_FP16)};
    const uint64_t skipping[] = {0, 1, 7, 1000, 1ull << 40, (1ull << 40) + 3, ~0ull - 1, ~0ull};
    std::vector<std::vector<float>> results[2];
    for (int run = 0; run < 2; ++run) {
        rrc_context_desc d = rrc_test::context_desc(48, 32, channels);
        d.depth_mode = sc.depth_mode;
        d.reprojection = RRC_REPROJECTION_PREV_CLIP;
        rrc_test::Context ctx(d);
        ASSERT_TRUE(ctx);
        for (int t = 0; t < 8; ++t) {
            rrc_test::SceneFrameInputs in;
            in.frame = scene.render(t);
            rrc_test::make_frame_inputs(in, RRC_REPROJECTION_PREV_CLIP, {1, 4}, {false, false});
            in.desc.frame_index = run == 0 ? (uint64_t)t : skipping[t];
            rrc_test::FrameResult k = ctx.run(in.desc);
            results[run].push_back(k.values[0]);
            results[run].push_back(k.values[1]);
            results[run].push_back(std::vector<float>(k.mask.begin(), k.mask.end()));
        }
    }
    EXPECT_EQ(results[0], results[1]);
}

// A host that drops frames: frames 0, 1, 3, 4, 8, 9, 15 of a moving scene,
// each rendered against the previous one submitted.
TEST(SkippedIndices, ReprojectionIsAgainstTheLastFrameSubmitted) {
    rrc_scene::SceneConfig sc;
    sc.width = 96;
    sc.height = 64;
    sc.depth_mode = RRC_DEPTH_MODE_REVERSED;
    rrc_scene::Scene scene(sc);
    std::vector<rrc_channel_desc> channels = {channel("pcf", 1, 0.6f)};
    rrc_context_desc d = rrc_test::context_desc(96, 64, channels);
    d.depth_mode = sc.depth_mode;
    d.reprojection = RRC_REPROJECTION_PREV_CLIP;
    rrc_test::Context ctx(d);
    ASSERT_TRUE(ctx);
    const int submitted[] = {0, 1, 3, 4, 8, 9, 15};
    int64_t hits = 0, checked = 0, false_hits = 0;
    for (size_t k = 0; k < sizeof submitted / sizeof submitted[0]; ++k) {
        const int t = submitted[k], prev = k ? submitted[k - 1] : t - 1;
        rrc_test::SceneFrameInputs in;
        in.frame = scene.render(t, prev);
        rrc_test::make_frame_inputs(in, RRC_REPROJECTION_PREV_CLIP, {1}, {false});
        rrc_test::FrameResult r = ctx.run(in.desc);
        if (k == 0) continue;
        rrc_scene::FalseHitReport fh = rrc_scene::count_false_hits(scene, t, prev, r.mask.data());
        hits += (int64_t)r.stats.hits;
        checked += fh.hits_checked;
        false_hits += fh.false_hits;
        EXPECT_GT(r.stats.hits, (uint64_t)(96 * 64) / 2) << "frame " << t << " against " << prev;
    }
    EXPECT_EQ(false_hits, 0);
    report("skipped frame indices", "frames 0,1,3,4,8,9,15 of a moving scene, each against the last submitted",
           "> 50% hits every frame, 0 false hits; indices 0..7 vs 0,1,7,1000,2^40,..: bit-identical",
           format("%lld hits (%lld checked), %lld false", (long long)hits, (long long)checked, (long long)false_hits));
}

}  // namespace
