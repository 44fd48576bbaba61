// Depth precision (docs/measurements/STABILITY.md, "Depth precision: FIXED and the ADAPTIVE default side by side"):
// the analytic scene (tests/scenes) with static
// geometry and a moving camera, PREV_CLIP reprojection, 96x64, 8 frames,
// across near/far ratios 1e2 .. 1e9 in standard-Z float depth (precision
// collapses far away: z = 1 - n/d rounds to 1, i.e. to background), reversed-Z
// with a finite and an infinite far plane, and unorm16 / unorm24 depth with
// their default epsilon (one z increment).
//
// Per case, against exact visibility (docs/CONVENTIONS.md, scenes/false_hits.h):
//   hit ratio  kernel hits / pixels that should hit (their surface point was
//              visible last frame and every bilinear tap lies on it: TRUE_HIT
//              whether marked or not);
//   false hits hits on a surface point not visible last frame (rule 3), and
//              strict ones (a tap on another surface, rule 4);
//   lost       visible pixels whose stored depth reads as background.
// Asserted: reversed-Z float keeps >= 99% hits and 0 false hits (finite and
// infinite far, every ratio) with epsilon = 2^17 ulps of z; FIXED's 4 ulps
// keep 0 false hits on reversed-Z at a hit ratio of ~95% (the bilinear fetch
// of depth across a curved surface is off by far more than a few ulps of z);
// the 0.2 default (ADAPTIVE) keeps >= 99% and 0 false hits on every case the
// format resolves.  Every case is reported.
#include "scenes/false_hits.h"
#include "stability_report.h"
#include "support/rrc_test_context.h"
#include "support/scene_frames.h"

#include <cmath>
#include <limits>

using namespace rrc_test;

namespace {

struct DepthCase {
    std::string name;
    rrc_depth_mode mode;
    rrc_depth_format format;
    double near_plane, far_plane;
    float epsilon_scale;  // 0: the default (4 ulp for FLOAT32, 1 increment for UNORM)
    bool must_hold;       // >= 99% hits and 0 false hits asserted (else 0 false hits only where noted)
    bool no_false_hits;   // 0 false hits asserted
    rrc_depth_test test = RRC_DEPTH_TEST_DEFAULT;  // the context's depth_test
};

const double kInf = std::numeric_limits<double>::infinity();
// 2^17 ulps of z: 0.8% .. 1.6% of z, i.e. of the view depth for reversed-Z
// (z ~ n/d): LINEAR's default tau = 1% expressed in ulps.  The default 4 ulps cannot accept
// the bilinear depth fetch on curved surfaces (see docs/measurements/STABILITY.md).
constexpr float kWideUlps = 131072.0f;

std::vector<DepthCase> base_cases() {
    const auto S = RRC_DEPTH_MODE_STANDARD, R = RRC_DEPTH_MODE_REVERSED;
    const auto F = RRC_DEPTH_FORMAT_FLOAT32, U16 = RRC_DEPTH_FORMAT_UNORM16, U24 = RRC_DEPTH_FORMAT_UNORM24;
    return {
        {"standard_float_1e2", S, F, 1.0, 100.0, 0, false, false},
        {"standard_float_1e4", S, F, 1e-2, 100.0, 0, false, false},
        {"standard_float_1e6", S, F, 1e-4, 100.0, 0, false, false},
        {"standard_float_1e9", S, F, 1e-7, 100.0, 0, false, false},
        {"reversed_float_1e2", R, F, 1.0, 100.0, 0, false, true},
        {"reversed_float_1e9", R, F, 1e-7, 100.0, 0, false, true},
        {"reversed_float_infinite_near_1e-7", R, F, 1e-7, kInf, 0, false, true},
        {"reversed_float_1e2_eps_2^17_ulp", R, F, 1.0, 100.0, kWideUlps, true, true},
        {"reversed_float_1e4_eps_2^17_ulp", R, F, 1e-2, 100.0, kWideUlps, true, true},
        {"reversed_float_1e6_eps_2^17_ulp", R, F, 1e-4, 100.0, kWideUlps, true, true},
        {"reversed_float_1e9_eps_2^17_ulp", R, F, 1e-7, 100.0, kWideUlps, true, true},
        {"reversed_float_infinite_near_0.1_eps_2^17_ulp", R, F, 0.1, kInf, kWideUlps, true, true},
        {"reversed_float_infinite_near_1e-7_eps_2^17_ulp", R, F, 1e-7, kInf, kWideUlps, true, true},
        {"standard_unorm16_1e2", S, U16, 1.0, 100.0, 0, false, false},
        {"standard_unorm16_1e4", S, U16, 1e-2, 100.0, 0, false, false},
        {"standard_unorm24_1e2", S, U24, 1.0, 100.0, 0, false, false},
        {"standard_unorm24_1e4", S, U24, 1e-2, 100.0, 0, false, false},
        {"standard_unorm24_1e6", S, U24, 1e-4, 100.0, 0, false, false},
        {"reversed_unorm24_1e4", R, U24, 1e-2, 100.0, 0, false, false},
    };
}

// Every case at the default tolerance runs under both tests side by side
// (docs/CONVENTIONS.md "Which test"): FIXED, the paper's 0.1 default, whose
// rows keep their 0.1 assertions; and the 0.2 default (ADAPTIVE), which must
// keep >= 99% of the hits and no false hit wherever the format resolves the
// scene (standard-Z up to 1e4; at 1e9 standard float rounds to background).
std::vector<DepthCase> cases() {
    std::vector<DepthCase> all;
    for (DepthCase c : base_cases()) {
        if (c.epsilon_scale != 0) {
            all.push_back(c);  // a host epsilon: FIXED
            continue;
        }
        DepthCase fixed = c, adaptive = c;
        fixed.name += "_fixed";
        fixed.test = RRC_DEPTH_TEST_FIXED;
        adaptive.name += "_default";
        // Standard-Z at 1e6 and beyond has a z step of a few percent of d far
        // away (FIXED has false hits there too): beyond the range the ADAPTIVE
        // test is asserted on (standard float and unorm up to 1e4).
        const bool beyond = c.mode == RRC_DEPTH_MODE_STANDARD && c.far_plane / c.near_plane > 1e5;
        adaptive.must_hold = adaptive.no_false_hits = !beyond;
        all.push_back(fixed);
        all.push_back(adaptive);
    }
    return all;
}

// ctest shows the parameter: print its name, not its bytes.
void PrintTo(const DepthCase& c, std::ostream* os) { *os << c.name; }

// The case's scene of width x height: static geometry, moving camera.
rrc_scene::SceneConfig scene_of(const DepthCase& c, int width, int height) {
    rrc_scene::SceneConfig sc = scene_config(width, height, c.mode, c.format, c.far_plane);
    sc.near_plane = c.near_plane;
    sc.object_motion = false;
    return sc;
}

class DepthPrecision : public ::testing::TestWithParam<DepthCase> {};

TEST_P(DepthPrecision, HitRatioAndFalseHits) {
    const DepthCase& c = GetParam();
    const int W = 96, H = 64, frames = 8;
    rrc_scene::Scene scene(scene_of(c, W, H));

    std::vector<rrc_channel_desc> channels = {channel("s", 1, 0.6f)};
    rrc_context_desc d = scene_context_desc(scene.config(), RRC_REPROJECTION_PREV_CLIP, channels);
    d.epsilon_scale = c.epsilon_scale;
    d.depth_test = c.test;
    Context ctx(d);
    ASSERT_TRUE(ctx);

    int64_t should_hit = 0, true_hits = 0, hits = 0, false_hits = 0, strict = 0, visible = 0, lost = 0;
    rrc_scene::FalseHitOptions options;
    options.count_missed = true;
    for (int t = 0; t < frames; ++t) {
        SceneFrameInputs in;
        in.frame = scene.render(t);
        make_frame_inputs(in, RRC_REPROJECTION_PREV_CLIP, {1}, {false});
        FrameResult k = ctx.run(in.desc);
        if (t == 0) continue;
        rrc_scene::FalseHitReport fh = rrc_scene::count_false_hits(scene, t, k.mask.data(), options);
        const int64_t marked_true = fh.hits_checked - fh.strict_false_hits;
        true_hits += marked_true;
        should_hit += marked_true + fh.missed_visible;
        hits += (int64_t)k.stats.hits;
        false_hits += fh.false_hits;
        strict += fh.strict_false_hits;
        for (size_t i = 0; i < in.frame.object_id.size(); ++i) {
            if (in.frame.object_id[i] < 0) continue;
            ++visible;
            lost += (k.mask[i] & RRC_MASK_BACKGROUND) ? 1 : 0;
        }
    }
    const double ratio = should_hit ? double(true_hits) / should_hit : 0.0;
    rrc_stab::report("depth precision (static scene, camera motion, PREV_CLIP, 96x64, 7 frames)", c.name.c_str(),
                     c.must_hold       ? ">= 99% hits, 0 false hits"
                     : c.no_false_hits ? "0 false hits"
                                       : "reported",
                     rrc_stab::format("hit ratio %.2f%% (%lld / %lld), false hits %lld, strict %lld, lost to background %lld / %lld",
                                      100.0 * ratio, (long long)true_hits, (long long)should_hit, (long long)false_hits, (long long)strict,
                                      (long long)lost, (long long)visible));
    EXPECT_GT(should_hit, visible / 2) << "the scene should be mostly reprojectable";
    if (c.must_hold) EXPECT_GE(ratio, 0.99) << c.name;
    if (c.no_false_hits) {
        EXPECT_EQ(false_hits, 0) << c.name;
        EXPECT_EQ(lost, 0) << c.name;
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, DepthPrecision, ::testing::ValuesIn(cases()), [](const ::testing::TestParamInfo<DepthCase>& i) {
    std::string n = i.param.name;
    for (char& ch : n)
        if (ch == '-' || ch == '.' || ch == '^') ch = '_';
    return n;
});

}  // namespace
