// rrc-cache end to end, small, under the validation layer (RRC_VALIDATION=1
// from ctest; the host's own layer too): the miss shader runs on exactly the
// listed quads every frame; refreshing every hit every frame (n = 1) gives
// the full shading to fp16 precision; longer periods shade less and err more;
// the second eye of a stereo pair reuses the first eye's shading, and the
// sub-frames of a motion-blurred frame each other's.
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
    const std::vector<Figures> f = figures(runs);
    const Figures &none = f[1], &n1 = f[2], &n4 = f[3], &st = f[4];
    // Every cached run carries its paired baseline (the same frames shaded everywhere, timed beside them).
    for (size_t i = 1; i < f.size(); ++i) {
        EXPECT_GE(f[i].full_ms, f[i].raster_ms) << f[i].name;
        EXPECT_TRUE(f[i].bound > 0 && std::isfinite(f[i].bound)) << f[i].name;
        EXPECT_GT(f[i].speedup, 0.0) << f[i].name;
    }

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

}  // namespace
