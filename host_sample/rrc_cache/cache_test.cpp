// rrc-cache end to end, small, under the validation layer (RRC_VALIDATION=1
// from ctest; the host's own layer too): the miss shader runs on exactly the
// listed quads every frame; refreshing every hit every frame (n = 1) gives
// the full shading to fp16 precision; longer periods shade less and err more;
// the second eye of a stereo pair reuses the first eye's shading, and the
// sub-frames of a motion-blurred frame each other's.  The time model (the
// speed-up, the Amdahl bound) is tested on made-up timings only.
#include "cache_report.h"
#include "cache_run.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace rrc_cache;

TEST(RrcCache, MissShaderCoversTheListAndRefreshTradesErrorForWork) {
    Settings s;
    s.width = 96;
    s.height = 64;
    s.frames = 6;
    s.validation = true;
    Bench bench(s);
    std::vector<CacheConfig> cs = {{"full", false}, {"cache_no_refresh", true}};
    for (uint32_t n : {1u, 4u}) {
        CacheConfig c;
        c.name = "tiled_" + std::to_string(n);
        c.policy = RRC_REFRESH_TILED;
        c.period = n;
        cs.push_back(c);
    }
    CacheConfig stereo{"stereo_cache", true};
    stereo.stereo = true;
    cs.push_back(stereo);
    CacheConfig blur{"blur4_cache", true};
    blur.subframes = 4;
    cs.push_back(blur);
    std::vector<RunResult> runs;
    for (const CacheConfig& c : cs) {
        runs.push_back(bench.run(c, nullptr));
        EXPECT_TRUE(runs.back().list_matched) << c.name << ": the miss shader did not shade exactly the listed quads";
        EXPECT_EQ(runs.back().validation_messages, 0u) << c.name;
        for (const FrameRecord& f : runs.back().frames)
            if (c.cache) EXPECT_EQ(f.listed, f.shaded_quads) << c.name;
    }
    // Nothing here depends on measured times (a loaded machine may time a pass at 0): the time
    // model is tested on made-up timings below (RrcCacheReport).
    const std::vector<Figures> f = figures(runs);
    const Figures &none = f[1], &n1 = f[2], &n4 = f[3], &st = f[4];

    // n = 1 refreshes every hit every frame: the output is the frame's own shading (fp16 history).
    const RunResult& every = runs[2];
    ASSERT_EQ(every.image.size(), every.truth.size());
    double worst = 0;
    for (size_t i = 0; i < every.image.size(); ++i) {
        if (i % 4 == 3) continue;
        const double tol = std::ldexp(std::fabs(every.truth[i]), -11) + 1e-7;
        worst = std::max(worst, std::fabs(every.image[i] - every.truth[i]) / tol);
    }
    EXPECT_LE(worst, 1.0) << "n = 1 must reproduce the full shading to fp16 rounding";
    EXPECT_LT(n1.rmse, 1e-3);
    EXPECT_NEAR(n1.hit_fraction, 0.0, 1e-12) << "n = 1: no hit is reused";

    // Longer periods shade less and err more.
    EXPECT_GT(n1.shaded_fraction, n4.shaded_fraction);
    EXPECT_GT(n4.shaded_fraction, none.shaded_fraction);
    EXPECT_LT(n1.rmse, n4.rmse);
    EXPECT_LE(n4.rmse, none.rmse);
    EXPECT_GT(none.hit_fraction, 0.3) << "the cache must reuse most of the frame";

    // The second eye reuses the first eye's shading.
    ASSERT_FALSE(runs[4].mask_left.empty());
    size_t hits = 0;
    for (uint8_t m : runs[4].mask_left) hits += (m & RRC_MASK_HIT) ? 1 : 0;
    EXPECT_GT(hits, runs[4].mask_left.size() / 3) << "the second eye reprojects into the first eye's cache";
    EXPECT_LT(st.shaded_fraction, 0.9);

    // Motion blur: each sub-frame reuses the one before, so most of a frame's four sub-frames are not shaded.
    EXPECT_EQ(runs[5].frames.size(), 6u);
    EXPECT_LT(f[5].shaded_fraction, 0.9);
    EXPECT_GT(f[5].hit_fraction, 0.3);
}

// The time model (cache_report.h) on made-up medians: what the report prints follows from the times.
TEST(RrcCacheReport, TimeModelOnMadeUpTimings) {
    Figures f;
    f.raster_ms = 10, f.shade_ms = 4, f.rrc_ms = 6, f.total_ms = 20;  // this frame: 10 + 4 + 6
    f.full_shade_ms = 30, f.full_ms = 40;                             // the paired full frame: 10 + 30
    f.shaded_fraction = 0.25;
    apply_time_model(f, true);
    EXPECT_DOUBLE_EQ(f.p, 0.75);
    EXPECT_DOUBLE_EQ(f.c, 0.15);
    EXPECT_DOUBLE_EQ(f.bound, 1.0 / (0.25 + 0.75 * 0.25 + 0.15));
    EXPECT_DOUBLE_EQ(f.speedup, 2.0);
    EXPECT_DOUBLE_EQ(f.of_bound, 2.0 * (0.25 + 0.75 * 0.25 + 0.15));

    // Without the cache: c = 0 and the frame is its own baseline, bound 1 and speed-up 1.
    Figures full;
    full.raster_ms = 10, full.shade_ms = 30, full.total_ms = 40, full.full_shade_ms = 30, full.full_ms = 40, full.shaded_fraction = 1;
    full.rrc_ms = 5;  // ignored without the cache
    apply_time_model(full, false);
    EXPECT_DOUBLE_EQ(full.c, 0.0);
    EXPECT_DOUBLE_EQ(full.bound, 1.0);
    EXPECT_DOUBLE_EQ(full.speedup, 1.0);
    EXPECT_DOUBLE_EQ(full.of_bound, 1.0);

    // The cache costing more than it saves: bound and speed-up below 1.
    Figures slow = f;
    slow.rrc_ms = 30, slow.total_ms = 44;
    apply_time_model(slow, true);
    EXPECT_DOUBLE_EQ(slow.c, 0.75);
    EXPECT_LT(slow.bound, 1.0);
    EXPECT_DOUBLE_EQ(slow.speedup, 40.0 / 44.0);

    // Nothing measured (0 ms, as a loaded machine may report): every derived figure 0, none infinite.
    Figures zero = f;
    zero.total_ms = 0;
    apply_time_model(zero, true);
    EXPECT_EQ(zero.p, 0.0);
    EXPECT_EQ(zero.bound, 0.0);
    EXPECT_EQ(zero.speedup, 0.0);
    EXPECT_EQ(zero.of_bound, 0.0);
    zero = f;
    zero.full_ms = 0;
    apply_time_model(zero, true);
    EXPECT_EQ(zero.speedup, 0.0);

    // The bound: shading everything and shading nothing for free has none; of-bound is then 0, not NaN.
    EXPECT_DOUBLE_EQ(amdahl_bound(0.5, 0.5, 0.0), 1.0 / 0.75);
    EXPECT_TRUE(std::isinf(amdahl_bound(1.0, 0.0, 0.0)));
    Figures free = f;
    free.full_shade_ms = free.full_ms, free.shaded_fraction = 0, free.rrc_ms = 0;
    apply_time_model(free, true);
    EXPECT_TRUE(std::isinf(free.bound));
    EXPECT_EQ(free.of_bound, 0.0);

    EXPECT_DOUBLE_EQ(speedup_against(30.0, 20.0), 1.5);
    EXPECT_EQ(speedup_against(0.0, 20.0), 0.0);
    EXPECT_EQ(speedup_against(30.0, 0.0), 0.0);
}

}  // namespace
