// The fused kernel against the independent double-precision reference
// (tests/reference), one frame at a time on analytic scenes (tests/scenes):
// the reference takes the kernel's own previous history and age, so a pixel
// that flips at the epsilon threshold cannot spread through later frames.
//
// Per case and frame it asserts
//   - mask bits equal on every pixel not within the reference's stated margin
//     of a decision threshold (near_threshold);
//   - fp32 values within 1e-6 absolute + 1e-5 relative, fp16 values within
//     one fp16 step of the reference's rounding (and counts the exact ones);
//   - ages equal (except where the nearest texel is within fp32 error of a
//     texel edge: near_nearest_edge);
//   - zero false hits against exact visibility for PREV_CLIP and MOTION_DEPTH.
// With RRC_ACCURACY_REPORT=<file> set, the measured table is written there
// (docs/measurements/ACCURACY.md is made this way; see that file for the command).
#include "reference/rrc_reference.h"
#include "scenes/false_hits.h"
#include "support/rrc_test_context.h"
#include "support/scene_frames.h"
#include "support/tolerance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

using namespace rrc_test;

namespace {

const double kInf = std::numeric_limits<double>::infinity();

struct Case {
    const char* name;
    rrc_reprojection source;
    rrc_depth_mode depth_mode;
    rrc_depth_format depth_format;
    double far_plane;
    bool object_motion;  // CAMERA handles static geometry only
    bool jitter;
    double invalid_fraction;
    std::vector<rrc_channel_desc> channels;
    bool zero_false_hits;    // exact sources must never hit falsely
    bool object_id = false;  // the context takes the scene's object ids
};

std::vector<Case> cases() {
    auto ch = [](const char* n, uint32_t comps, float lambda, rrc_history_precision p, rrc_blend b, rrc_history_filter f, uint32_t cap = 0,
                 uint32_t conf = 0) { return channel(n, comps, lambda, p, b, f, cap, conf); };
    const auto fp16 = RRC_HISTORY_FP16, fp32 = RRC_HISTORY_FP32;
    const auto fixed = RRC_BLEND_FIXED, age = RRC_BLEND_AGE_AWARE, mean = RRC_BLEND_RUNNING_MEAN;
    const auto bil = RRC_HISTORY_FILTER_BILINEAR, nea = RRC_HISTORY_FILTER_NEAREST, cr = RRC_HISTORY_FILTER_CATMULL_ROM;
    auto chs = [](auto... c) { return std::vector<rrc_channel_desc>{c...}; };
    // Scene and context: source, depth mode, depth format.
    const auto clip = RRC_REPROJECTION_PREV_CLIP, md = RRC_REPROJECTION_MOTION_DEPTH, mv = RRC_REPROJECTION_MOTION,
               cam = RRC_REPROJECTION_CAMERA;
    const auto S = RRC_DEPTH_MODE_STANDARD, R = RRC_DEPTH_MODE_REVERSED, L = RRC_DEPTH_MODE_LINEAR;
    const auto F = RRC_DEPTH_FORMAT_FLOAT32, U16 = RRC_DEPTH_FORMAT_UNORM16, U24 = RRC_DEPTH_FORMAT_UNORM24;
    return {
        {"prev_clip_standard_float32", clip, S, F, 100, true, true, 0,
         chs(ch("pcf", 1, 0.6f, fp32, fixed, bil), ch("env", 4, 0.6f, fp16, age, cr)), true},
        {"prev_clip_reversed_infinite", clip, R, F, kInf, true, true, 0,
         chs(ch("soft", 1, 0.0f, fp16, mean, nea, 16), ch("env", 4, 0.8f, fp32, fixed, bil, 0, 1)), true},
        {"prev_clip_reversed_finite", clip, R, F, 100, true, false, 0, chs(ch("pcf", 1, 0.6f, fp32, age, cr, 0, 1)), true},
        {"prev_clip_linear", clip, L, F, 100, true, true, 0,
         chs(ch("pcf", 1, 0.6f, fp32, fixed, bil), ch("soft", 1, 0.0f, fp32, mean, bil, 8)), true},
        {"prev_clip_standard_unorm16", clip, S, U16, 100, true, false, 0, chs(ch("pcf", 1, 0.6f, fp16, fixed, bil)), false},
        {"prev_clip_standard_unorm24", clip, S, U24, 100, true, false, 0, chs(ch("pcf", 1, 0.6f, fp16, fixed, bil)), false},
        {"motion_depth_reversed", md, R, F, 100, true, true, 0,
         chs(ch("pcf", 1, 0.6f, fp32, fixed, bil), ch("env", 4, 0.6f, fp16, fixed, bil)), true},
        {"motion_depth_linear", md, L, F, 100, true, false, 0, chs(ch("pcf", 1, 0.6f, fp32, age, bil)), true},
        {"motion_standard_linearised", mv, S, F, 100, true, true, 0, chs(ch("pcf", 1, 0.6f, fp32, fixed, bil)), false},
        {"motion_reversed_infinite", mv, R, F, kInf, true, false, 0, chs(ch("pcf", 1, 0.6f, fp16, fixed, cr)), false},
        {"motion_linear", mv, L, F, 100, true, false, 0, chs(ch("pcf", 1, 0.6f, fp32, fixed, nea)), false},
        {"camera_standard", cam, S, F, 100, false, true, 0, chs(ch("pcf", 1, 0.6f, fp32, fixed, bil), ch("env", 4, 0.6f, fp16, age, bil)),
         false},
        {"camera_reversed_infinite", cam, R, F, kInf, false, false, 0, chs(ch("pcf", 1, 0.6f, fp32, fixed, bil)), false},
        {"camera_linear", cam, L, F, 100, false, true, 0, chs(ch("pcf", 1, 0.6f, fp32, mean, bil, 32)), false},
        {"invalid_samples", clip, R, F, 100, true, false, 0.03,
         chs(ch("pcf", 1, 0.6f, fp32, fixed, bil), ch("env", 4, 0.6f, fp16, age, bil, 0, 1)), true},
        {"prev_clip_standard_object_id", clip, S, F, 100, true, true, 0, chs(ch("pcf", 1, 0.6f, fp32, fixed, bil)), true, true},
        {"camera_linear_object_id", cam, L, F, 100, false, true, 0, chs(ch("pcf", 1, 0.6f, fp16, fixed, bil)), false, true},
    };
}

// The case's analytic scene of width x height.
rrc_scene::SceneConfig scene_of(const Case& c, int width, int height) {
    rrc_scene::SceneConfig sc = scene_config(width, height, c.depth_mode, c.depth_format, c.far_plane);
    sc.object_motion = c.object_motion;
    sc.jitter = c.jitter;
    sc.invalid_fraction = c.invalid_fraction;
    return sc;
}

struct Row {
    std::string name, test, tolerance;
    double max_fp32_error = 0, max_fp16_steps = 0, fp16_exact_ratio = 1;
    double max_position_ratio = 0;  // max (error - arithmetic tolerance) / (spread * coordinate resolution)
    int64_t pixels = 0, compared = 0, near_threshold = 0, flips_in_margin = 0, near_edge = 0, mask_mismatch = 0;
    int64_t hits = 0, hits_checked = 0, false_hits = 0, strict_false_hits = 0;
    int64_t missed_visible = 0;  // misses whose point the false-hit rule calls visible (tests/scenes/false_hits.h)
};
std::vector<Row>& report() {
    static std::vector<Row> rows;
    return rows;
}

// Every case runs under both depth tests (docs/CONVENTIONS.md "Which test"):
// FIXED, the paper's, and the 0.2 default (ADAPTIVE for every source but plain
// MOTION, whose relative test is the same under both).
using Param = std::tuple<Case, rrc_depth_test>;
const char* test_name(rrc_depth_test t) { return t == RRC_DEPTH_TEST_FIXED ? "fixed" : "default"; }

class KernelVsReference : public ::testing::TestWithParam<Param> {};

TEST_P(KernelVsReference, OneFrameAtATime) {
    const Case& c = std::get<0>(GetParam());
    const rrc_depth_test test = std::get<1>(GetParam());
    const int W = 96, H = 64, frames = 10;
    rrc_scene::Scene scene(scene_of(c, W, H));
    rrc_context_desc desc = scene_context_desc(scene.config(), c.source, c.channels);
    desc.depth_test = test;
    desc.use_object_id = c.object_id ? 1u : 0u;
    Context ctx(desc);
    ASSERT_TRUE(ctx);

    Row row;
    row.name = c.name;
    row.test = test == RRC_DEPTH_TEST_FIXED ? "FIXED" : c.source == RRC_REPROJECTION_MOTION ? "default (FIXED)" : "default (ADAPTIVE)";
    int64_t fp16_values = 0, fp16_exact = 0;
    rrc_ref::PreviousFrame prev;
    for (int t = 0; t < frames; ++t) {
        SceneFrameInputs in;
        in.frame = scene.render(t);
        make_frame_inputs(in, c.source, c.channels);
        FrameResult k = ctx.run(in.desc);
        rrc_ref::FrameResult r = rrc_ref::run_frame(ctx.desc(), prev, in.desc);
        const size_t n = (size_t)W * H;
        for (size_t i = 0; i < n; ++i) {
            ++row.pixels;
            if (r.near_threshold[i]) {
                ++row.near_threshold;
                if (k.mask[i] != r.mask[i]) {  // a legitimate flip within the margin
                    ++row.flips_in_margin;
                    continue;
                }
            } else if (k.mask[i] != r.mask[i]) {
                ++row.mask_mismatch;
                ADD_FAILURE_AT(__FILE__, __LINE__)
                    << c.name << " frame " << t << " pixel (" << i % W << "," << i / W << ") mask " << int(k.mask[i]) << " reference "
                    << int(r.mask[i]) << " diff " << r.diff[i] << " eps " << r.eps[i];
                continue;
            }
            if (r.near_nearest_edge[i]) {
                ++row.near_edge;
                continue;
            }
            ++row.compared;
            for (size_t ch = 0; ch < c.channels.size(); ++ch) {
                EXPECT_EQ(k.age[ch][i], r.channels[ch].age[i]) << c.name << " frame " << t << " pixel " << i << " channel " << ch;
                const uint32_t m = c.channels[ch].components;
                for (uint32_t q = 0; q < m; ++q) {
                    double kv = k.values[ch][m * i + q], rv = r.channels[ch].out[m * i + q];
                    double err = std::fabs(kv - rv);
                    double spread = prev.valid ? history_spread(prev.channels[ch].history, m, q, W, H, r.uv_prev_x[i], r.uv_prev_y[i],
                                                                in.desc.prev_jitter)
                                               : 0.0;
                    const bool fp16 = c.channels[ch].precision == RRC_HISTORY_FP16;
                    double arithmetic = arithmetic_tolerance(rv, r.channels[ch].exact[m * i + q], fp16);
                    double position = position_tolerance(spread, W, H);
                    if (err > arithmetic && spread > 0)
                        row.max_position_ratio =
                            std::max(row.max_position_ratio, (err - arithmetic) / (spread * coordinate_resolution(W, H)));
                    if (c.channels[ch].precision == RRC_HISTORY_FP32) {
                        row.max_fp32_error = std::max(row.max_fp32_error, err);
                    } else {
                        row.max_fp16_steps = std::max(row.max_fp16_steps, err / fp16_step(r.channels[ch].exact[m * i + q]));
                        ++fp16_values;
                        fp16_exact += err == 0 ? 1 : 0;
                    }
                    EXPECT_LE(err, arithmetic + position) << c.name << " frame " << t << " pixel " << i << " channel " << ch << " kernel "
                                                          << kv << " reference " << rv << " spread " << spread;
                    EXPECT_TRUE(std::isfinite(kv)) << c.name << " pixel " << i;
                }
                if (c.channels[ch].confidence) {
                    double err = std::fabs(k.weight[ch][i] - r.channels[ch].weight[i]);
                    row.max_fp32_error = std::max(row.max_fp32_error, err);
                    EXPECT_LE(err, 1e-6 + 1e-5 * std::fabs(r.channels[ch].weight[i])) << c.name << " weight pixel " << i;
                }
            }
        }
        if (t > 0) {
            rrc_scene::FalseHitOptions options;
            options.count_missed = true;
            rrc_scene::FalseHitReport fh = rrc_scene::count_false_hits(scene, t, k.mask.data(), options);
            row.missed_visible += fh.missed_visible;
            row.hits += (int64_t)k.stats.hits;
            row.hits_checked += fh.hits_checked;
            row.false_hits += fh.false_hits;
            row.strict_false_hits += fh.strict_false_hits;
        }
        // The next frame's reference starts from the kernel's stored state.
        prev.valid = true;
        prev.depth = in.frame.depth;
        prev.object_id = in.object_id;
        prev.channels.resize(c.channels.size());
        for (size_t ch = 0; ch < c.channels.size(); ++ch) {
            prev.channels[ch].history = k.values[ch];
            prev.channels[ch].age = k.age[ch];
            prev.channels[ch].weight = k.weight[ch];
        }
    }
    row.fp16_exact_ratio = fp16_values ? double(fp16_exact) / fp16_values : 1.0;
    std::printf(
        "%-30s %-8s compared %lld/%lld near-threshold %lld (flipped %lld) near-edge %lld mask-mismatch %lld hits %lld false %lld strict "
        "%lld "
        "missed visible %lld max fp32 err %.3g max fp16 steps %.3g position ratio %.3g\n",
        c.name, test_name(test), (long long)row.compared, (long long)row.pixels, (long long)row.near_threshold,
        (long long)row.flips_in_margin, (long long)row.near_edge, (long long)row.mask_mismatch, (long long)row.hits,
        (long long)row.false_hits, (long long)row.strict_false_hits, (long long)row.missed_visible, row.max_fp32_error, row.max_fp16_steps,
        row.max_position_ratio);
    if (c.zero_false_hits) EXPECT_EQ(row.false_hits, 0) << c.name;
    EXPECT_GT(row.hits, 0) << c.name << ": a case without hits tests nothing";
    EXPECT_GT(row.compared, row.pixels * 9 / 10) << c.name << ": too few pixels compared";
    bool has16 = false, has32 = false;
    for (auto& ch : c.channels) (ch.precision == RRC_HISTORY_FP16 ? has16 : has32) = true;
    row.tolerance = std::string(has32 ? "fp32" : "") + (has16 && has32 ? "+" : "") + (has16 ? "fp16" : "");
    report().push_back(row);
}

INSTANTIATE_TEST_SUITE_P(Cases, KernelVsReference,
                         ::testing::Combine(::testing::ValuesIn(cases()), ::testing::Values(RRC_DEPTH_TEST_FIXED, RRC_DEPTH_TEST_DEFAULT)),
                         [](const ::testing::TestParamInfo<Param>& i) {
                             return std::string(std::get<0>(i.param).name) + "_" + test_name(std::get<1>(i.param));
                         });

// Writes the measured table when asked: RRC_ACCURACY_REPORT names a markdown
// file whose text between the two markers below is replaced (docs/measurements/ACCURACY.md).
class AccuracyReport : public ::testing::Environment {
public:
    void TearDown() override {
        const char* path = std::getenv("RRC_ACCURACY_REPORT");
        if (!path || report().empty()) return;
        const std::string begin = "<!-- kernel-vs-reference table: begin -->", end = "<!-- kernel-vs-reference table: end -->";
        std::ifstream in(path);
        std::stringstream doc;
        doc << in.rdbuf();
        std::string text = doc.str();
        size_t b = text.find(begin), e = text.find(end);
        if (b == std::string::npos || e == std::string::npos || e < b) {
            ADD_FAILURE() << path << " lacks the table markers";
            return;
        }
        std::ostringstream table;
        table << begin << "\n"
              << "| case | test | tolerance | max fp32 error | max fp16 steps | fp16 exact | position ratio | pixels compared "
                 "| near threshold | flipped within margin | mask mismatches | hits | hits checked | false hits | strict false hits | "
                 "visible pixels missed |\n"
                 "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
        for (const Row& r : report()) {
            char line[640];
            std::snprintf(
                line, sizeof line,
                "| %s | %s | %s | %.3g | %.3g | %.2f%% | %.3g | %lld / %lld | %lld | %lld | %lld | %lld | %lld | %lld | %lld | %lld |\n",
                r.name.c_str(), r.test.c_str(), r.tolerance.c_str(), r.max_fp32_error, r.max_fp16_steps, 100.0 * r.fp16_exact_ratio,
                r.max_position_ratio, (long long)r.compared, (long long)r.pixels, (long long)r.near_threshold, (long long)r.flips_in_margin,
                (long long)r.mask_mismatch, (long long)r.hits, (long long)r.hits_checked, (long long)r.false_hits,
                (long long)r.strict_false_hits, (long long)r.missed_visible);
            table << line;
        }
        text.replace(b, e - b, table.str());
        std::ofstream(path) << text;
    }
};
const ::testing::Environment* const kReport = ::testing::AddGlobalTestEnvironment(new AccuracyReport);

}  // namespace
