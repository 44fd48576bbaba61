// rrc-cache end to end, small, under the validation layer (RRC_VALIDATION=1
// from ctest; the host's own layer too): the miss shader runs on exactly the
// listed quads every frame; refreshing every hit every frame (n = 1) gives
// the full shading to fp16 precision; longer periods shade less and err more;
// the second eye of a stereo pair reuses the first eye's shading, and the
// sub-frames of a motion-blurred frame each other's; the shader's octave
// count (its cost) changes the shading, and 64 octaves stay finite.  The time
// model (the speed-up, the Amdahl bound, the break-even shader, the targets'
// verdicts) is tested on made-up timings only.
#include "cache_report.h"
#include "cache_run.h"
#include "cache_targets.h"
#include "spec_constant.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace {

using namespace rrc_cache;

// The tests' runs: 96x64 under the validation layer.
Settings tiny(uint32_t frames) {
    Settings s;
    s.width = 96;
    s.height = 64;
    s.frames = frames;
    s.validation = true;
    return s;
}

TEST(RrcCache, MissShaderCoversTheListAndRefreshTradesErrorForWork) {
    Bench bench(tiny(6));
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

double max_abs_diff(const std::vector<float>& a, const std::vector<float>& b) {
    double d = 0;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i)
        if (i % 4 != 3) d = std::max(d, (double)std::fabs(a[i] - b[i]));
    return d;
}

std::string read_text(const std::string& path) {
    std::ifstream f(path);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// perlin.glsl's kOctaves: the octave count is the shader's cost.  It changes the picture (each octave
// adds detail at half the amplitude of the one before), and 64 octaves, whose lattice coordinates leave
// int's range without perlin_cell's wrap, give finite values; the report and CSVs carry the octaves.
TEST(RrcCache, OctavesChangeTheShadingAndStayFiniteAt64) {
    const Settings s = tiny(4);
    Bench bench(s);
    std::vector<RunResult> runs;
    for (uint32_t octaves : {8u, 16u, 64u}) {
        const std::string suffix = octaves == 8 ? "" : "_o" + std::to_string(octaves);
        CacheConfig full{"full" + suffix, false};
        full.octaves = octaves;
        CacheConfig tiled{"tiled_4" + suffix, true};
        tiled.policy = RRC_REFRESH_TILED;
        tiled.period = 4;
        tiled.octaves = octaves;
        for (const CacheConfig& c : {full, tiled}) {
            runs.push_back(bench.run(c, nullptr));
            EXPECT_EQ(runs.back().validation_messages, 0u) << c.name;
            EXPECT_TRUE(runs.back().list_matched) << c.name;
        }
    }
    const std::vector<float>&o8 = runs[0].image, &o16 = runs[2].image, &o64 = runs[4].image;
    ASSERT_EQ(o8.size(), 4u * s.width * s.height);
    const double d_8_16 = max_abs_diff(o8, o16), d_16_64 = max_abs_diff(o16, o64);
    EXPECT_GT(d_8_16, 1e-4) << "16 octaves must shade differently from 8";
    EXPECT_LT(d_16_64, d_8_16) << "octaves past 16 add less than octaves 9-16 (halving amplitudes)";
    for (const std::vector<float>* img : {&o64, (const std::vector<float>*)&runs[5].image, (const std::vector<float>*)&runs[5].truth})
        for (float v : *img) ASSERT_TRUE(std::isfinite(v)) << "64 octaves must give finite values";
    EXPECT_EQ(runs[0].image, runs[1].truth) << "the same frame, the same shader, both ways shaded everywhere";

    // The report and the CSVs carry the octave count, the cost curve and the targets.
    const std::vector<Figures> f = figures(runs);
    const std::string dir = ::testing::TempDir();
    write_csv(dir + "/runs.csv", f);
    write_cost_csv(dir + "/speedup_vs_cost.csv", f);
    write_report(dir + "/report.md", f, "rrc-cache (test)", bench.device_name(), s);
    const std::string csv = read_text(dir + "/runs.csv"), cost = read_text(dir + "/speedup_vs_cost.csv"),
                      report = read_text(dir + "/report.md");
    EXPECT_NE(csv.find(",octaves\n"), std::string::npos) << csv;
    EXPECT_NE(csv.find("tiled_4_o64,"), std::string::npos);
    EXPECT_EQ(cost.rfind("octaves,run,full_shade_ms,full_ms,speedup,amdahl_bound,of_bound,c,shaded_fraction,rmse\n", 0), 0u) << cost;
    EXPECT_EQ(std::count(cost.begin(), cost.end(), '\n'), 4) << "a header and one row an octave count: " << cost;
    EXPECT_NE(cost.find("\n64,tiled_4_o64,"), std::string::npos) << cost;
    for (const char* text : {"| octaves |", "c = classify+resolve / full frame", "speed-up / bound", "Speed-up against shader cost",
                             "Break-even (speed-up = 1)", "1.7-1.9", "## Targets", "break-even shader at TILED n = 4",
                             "classify + resolve <= 0.40", "0.85 x the Amdahl bound"})
        EXPECT_NE(report.find(text), std::string::npos) << text;
}

// The octave count reaches the shader as its specialization constant's default (spec_constant.h).
TEST(RrcCacheReport, SpecConstantDefaultIsRewritten) {
    // A minimal module: the header, OpDecorate %7 SpecId 0, OpDecorate %9 SpecId 3, %7 = OpSpecConstant %2 8,
    // %9 = OpSpecConstant %2 5.
    const std::vector<uint32_t> m = {0x07230203u, 0x00010300u, 0, 10, 0,     (4u << 16) | 71, 7, 1, 0, (4u << 16) | 71, 9, 1, 3,
                                     (4u << 16) | 50, 2, 7, 8, (4u << 16) | 50, 2, 9, 5};
    EXPECT_EQ(spec_constant(m, 0), 8u);
    const std::vector<uint32_t> w = with_spec_constant(m.data(), 4 * m.size(), 0, 64);
    EXPECT_EQ(spec_constant(w, 0), 64u);
    EXPECT_EQ(spec_constant(w, 3), 5u) << "the other constant is left alone";
    EXPECT_EQ(w.size(), m.size());
    EXPECT_THROW(with_spec_constant(m.data(), 4 * m.size(), 1, 64), std::runtime_error) << "no SpecId 1";
    std::vector<uint32_t> bad = m;
    bad[0] = 0;
    EXPECT_THROW(spec_constant(bad, 0), std::runtime_error) << "not SPIR-V";
}

Figures made_up(const std::string& name, bool cache, uint32_t octaves, double shade_ms, double speedup, double of_bound, double c) {
    Figures f;
    f.name = name;
    f.config.name = name;
    f.config.cache = cache;
    if (cache) f.config.policy = RRC_REFRESH_TILED, f.config.period = 4;
    f.config.octaves = octaves;
    f.full_shade_ms = shade_ms, f.full_ms = shade_ms + 10, f.speedup = speedup, f.of_bound = of_bound, f.c = c;
    f.bound = speedup / of_bound;
    return f;
}

// The cost curve, the break-even shader and the targets' verdicts (cache_targets.h) on made-up figures.
TEST(RrcCacheReport, BreakEvenAndVerdictsOnMadeUpFigures) {
    std::vector<Figures> fs = {made_up("full", false, 8, 10, 1, 1, 0),           made_up("tiled_4", true, 8, 10, 0.6, 0.9, 0.5),
                               made_up("tiled_4_o32", true, 32, 40, 1.2, 0.95, 0.1), made_up("tiled_4_o16", true, 16, 20, 0.9, 0.8, 0.3)};
    Figures lifetime = made_up("tiled_4_L8", true, 8, 10, 5.0, 1.0, 0.2);  // not on the curve: a lifetime
    lifetime.config.lifetime = 8;
    fs.push_back(lifetime);
    const std::vector<CostPoint> curve = cost_curve(fs);
    ASSERT_EQ(curve.size(), 3u);
    EXPECT_EQ(curve[0].octaves, 8u);
    EXPECT_EQ(curve[1].octaves, 16u) << "sorted by octaves";
    EXPECT_EQ(curve[2].run, "tiled_4_o32");
    EXPECT_DOUBLE_EQ(curve[1].shade_ms, 20.0);

    // 0.9 at 16 octaves (20 ms), 1.2 at 32 (40 ms): 1 a third of the way, 21.33 octaves, 26.67 ms.
    BreakEven b = break_even(curve);
    EXPECT_EQ(b.kind, BreakEven::kBetween);
    EXPECT_NEAR(b.octaves, 16 + 16.0 / 3, 1e-12);
    EXPECT_NEAR(b.shade_ms, 20 + 20.0 / 3, 1e-12);
    EXPECT_EQ(break_even({}).kind, BreakEven::kUnmeasured);
    std::vector<CostPoint> above = curve;
    for (CostPoint& p : above) p.speedup += 1;
    b = break_even(above);
    EXPECT_EQ(b.kind, BreakEven::kAtOrBelow);
    EXPECT_EQ(b.octaves, 8);
    std::vector<CostPoint> below = curve;
    for (CostPoint& p : below) p.speedup = 0.5;
    EXPECT_EQ(break_even(below).kind, BreakEven::kNotReached);
    std::vector<CostPoint> exact = curve;
    exact[1].speedup = 1.0;  // exactly 1 at a measured point: break-even there
    b = break_even(exact);
    EXPECT_EQ(b.kind, BreakEven::kBetween);
    EXPECT_DOUBLE_EQ(b.octaves, 16.0);

    Settings s;
    s.width = 640, s.height = 360;
    std::vector<Verdict> v = verdicts(fs, s);
    ASSERT_EQ(v.size(), 3u);
    EXPECT_FALSE(v[0].met) << "c = 0.5 at 8 octaves (tiled_4) > 0.40";
    EXPECT_NE(v[0].verdict.find("missed by 0.100"), std::string::npos) << v[0].verdict;
    EXPECT_FALSE(v[1].met) << "break-even at 21.3 octaves > 16";
    EXPECT_NE(v[1].verdict.find("missed by 5.3 octaves"), std::string::npos) << v[1].verdict;
    EXPECT_FALSE(v[2].met) << "0.8 of the bound at 16 octaves < 0.85";
    EXPECT_NE(v[2].verdict.find("missed by 0.05"), std::string::npos) << v[2].verdict;
    EXPECT_NE(v[2].measured.find("tiled_4_o16"), std::string::npos) << v[2].measured;

    // Every target met.
    fs[1].c = 0.35, fs[1].speedup = 1.1, fs[3].of_bound = 0.9;
    fs[4].c = 0.4;
    v = verdicts(fs, s);
    for (const Verdict& k : v) EXPECT_TRUE(k.met) << k.target << ": " << k.verdict;
    EXPECT_EQ(v[0].verdict, "met");
    EXPECT_NE(v[1].measured.find("<= 8 octaves"), std::string::npos) << v[1].measured;

    // Another size: the verdict says the target is stated at 640x360.
    s.width = 96, s.height = 64;
    EXPECT_NE(verdicts(fs, s)[0].verdict.find("640x360"), std::string::npos);
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
