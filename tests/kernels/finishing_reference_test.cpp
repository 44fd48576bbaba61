// API 0.4's finishing steps (docs/CONVENTIONS.md, "Finishing steps (0.4)")
// against the independent double-precision reference (tests/reference/finish.h),
// standalone (rrc_frame_run) on a moving analytic scene (tests/scenes):
//   - rectification: gamma 1 and 2.5, 1 and 4 components, fp16 and fp32, with
//     confidence, on noisy samples whose signal changes (a brightening front
//     sweeps the image), one frame at a time from the kernel's own previous
//     state as tests/kernels/kernel_reference_test.cpp does;
//   - the GAUSSIAN history filter: blur_sigma default and 0.8, the same mix;
//   - the spatial fill: fill_age 4 and 8, radius 1 and 2, with and without a
//     fallback, RUNNING_MEAN and REUSE channels, in each depth mode: the output
//     values are the displayed value, the reference's fill of a twin context's
//     (same channels without the fill) history; ages, masks and every value of
//     a pixel that is not filled equal the twin's exactly, every frame, so the
//     fill never entered history.
// Each case also runs the reference with a deliberately wrong variant (gamma
// ignored, rectification off, the blur missing or of the other sigma, the
// fill's fade missing, the fallback ignored, the other radius) and requires
// that the comparison would have caught it on enough pixels.
// Every context runs under the validation layer (support/rrc_test_context.h).
#include "reference/finish.h"
#include "reference/rrc_reference.h"
#include "reference/selftest_scene.h"
#include "support/cache_policy.h"
#include "support/fill_channel.h"
#include "support/kernel_state.h"
#include "support/mismatches.h"
#include "support/rrc_test_context.h"
#include "support/scene_frames.h"
#include "support/split_frame.h"
#include "support/tolerance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>
#include <string>

using namespace rrc_test;

namespace {

const int kW = 64, kH = 40, kFrames = 6;
// A wrong variant must differ beyond the tolerance on at least this many
// compared values over the case's frames.
const int64_t kMinCaught = 20;

rrc_scene::SceneConfig scene_of(rrc_depth_mode mode, double invalid_fraction = 0.0) {
    rrc_scene::SceneConfig sc = scene_config(kW, kH, mode);
    sc.jitter = true;
    sc.object_motion = true;
    sc.invalid_fraction = invalid_fraction;
    return sc;
}

// A changing signal: a front sweeping right by 6 pixels a frame brightens
// what it passes by 0.5 (the history behind it no longer matches).
void change_signal(rrc_scene::Frame& f, int t) {
    const int front = 6 * t;
    for (int j = 0; j < f.height; ++j)
        for (int i = 0; i < std::min(front, f.width); ++i) {
            const size_t p = (size_t)j * f.width + i;
            f.signal1[p] += 0.5f;
            for (int k = 0; k < 4; ++k) f.signal4[4 * p + k] += 0.125f * (k + 1);
        }
}

// The value tolerance of tests/support/tolerance.h plus what the reference says
// rectification's fp32 box adds.
double value_tolerance(const rrc_ref::ChannelResult& r, const rrc_ref::PreviousFrame& prev, size_t ch, uint32_t m, size_t i, uint32_t q,
                       bool fp16, const rrc_ref::FrameResult& fr, const float* prev_jitter) {
    const double spread =
        prev.valid ? history_spread(prev.channels[ch].history, m, q, kW, kH, fr.uv_prev_x[i], fr.uv_prev_y[i], prev_jitter) : 0.0;
    return arithmetic_tolerance(r.out[m * i + q], r.exact[m * i + q], fp16) + position_tolerance(spread, kW, kH) + r.rectify_err[m * i + q];
}

// A wrong variant of the context's channels, for the reference only.
struct Mutant {
    std::string name;
    size_t channel;
    std::function<void(rrc_channel_desc&)> change;
};

struct CaseStats {
    int64_t compared = 0, skipped = 0, hits = 0, refreshed = 0, rectified = 0, rectified_refreshed = 0;
    int64_t shortened = 0, dropped = 0, uncertain = 0;  // the lag detector: n_a < n_prev, n_a = 0, n_a within fp32 error of a step
    int64_t capped = 0, blur_uncertain = 0;             // the blur bound: N < n_prev, the stored age within fp32 error of a step
    int64_t view_capped = 0, view_uncertain = 0;        // the view lobe: n_v < n_prev, the stored age within fp32 error of a step
    double max_theta = 0.0;                             // the view lobe: the largest view turn it saw
    int64_t turn_caught = 0;                            // the lighting's turn: values the reference without it gets wrong
    double max_fp32_err = 0, max_fp16_steps = 0;
    std::vector<int64_t> caught;  // per mutant
};

// Runs `channels` on the scene for kFrames frames, comparing every frame with
// the reference from the kernel's previous state; returns the statistics.
CaseStats run_accumulating(const char* name, const std::vector<rrc_channel_desc>& channels, const std::vector<Mutant>& mutants,
                           bool changing_signal, const Policy* policy = nullptr, bool camera_positions = false, float lighting_turn = 0.0f) {
    CaseStats st;
    st.caught.assign(mutants.size(), 0);
    // A few invalid samples: rectification leaves such taps out of its box.
    rrc_scene::Scene scene(scene_of(RRC_DEPTH_MODE_REVERSED, 0.01));
    const rrc_reprojection source = RRC_REPROJECTION_PREV_CLIP;
    rrc_context_desc desc = scene_context_desc(scene.config(), source, channels);
    if (policy) apply(*policy, desc);
    Context ctx(desc);
    if (!ctx) {
        ADD_FAILURE() << name << ": context refused";
        return st;
    }
    // The mutants' contexts (reference only).
    std::vector<std::vector<rrc_channel_desc>> mutant_channels(mutants.size(), channels);
    std::vector<rrc_context_desc> mutant_desc(mutants.size(), ctx.desc());
    for (size_t m = 0; m < mutants.size(); ++m) {
        mutants[m].change(mutant_channels[m][mutants[m].channel]);
        mutant_desc[m].channels = mutant_channels[m].data();
    }

    Mismatches masks(std::string(name) + " mask"), ages(std::string(name) + " age"), values(std::string(name) + " value"),
        weights(std::string(name) + " weight");
    rrc_ref::PreviousFrame prev;
    const size_t n = (size_t)kW * kH;
    for (int t = 0; t < kFrames; ++t) {
        SceneFrameInputs in;
        in.frame = scene.render(t);
        if (changing_signal) change_signal(in.frame, t);
        make_frame_inputs(in, source, channels);
        if (camera_positions) {
            // The view lobe's eyes (docs/CONVENTIONS.md, "The view-dependent history").
            const glm::dvec3 eye = scene.camera(t).eye, prev_eye = scene.camera(std::max(t - 1, 0)).eye;
            for (int k = 0; k < 3; ++k) in.desc.camera_position[k] = eye[k], in.desc.prev_camera_position[k] = prev_eye[k];
        }
        // The lighting's turn (0.8), a different one each frame; the wrong variant ignores it.
        in.desc.lighting_turn = lighting_turn * (t % 3 + 1) / 3.0f;
        rrc_frame_desc still = in.desc;
        still.lighting_turn = 0.0f;
        FrameResult k = ctx.run(in.desc);
        rrc_ref::FrameResult r = rrc_ref::run_frame(ctx.desc(), prev, in.desc);
        std::vector<rrc_ref::FrameResult> mr;
        for (size_t m = 0; m < mutants.size(); ++m) mr.push_back(rrc_ref::run_frame(mutant_desc[m], prev, in.desc));
        const rrc_ref::FrameResult r_still = lighting_turn > 0.0f ? rrc_ref::run_frame(ctx.desc(), prev, still) : rrc_ref::FrameResult{};
        for (size_t i = 0; i < n; ++i) {
            // Pixels whose hit decision or nearest texel sits within fp32 error of a threshold.
            if (r.near_threshold[i] || r.near_nearest_edge[i]) {
                ++st.skipped;
                continue;
            }
            if (k.mask[i] != r.mask[i])
                masks.add() << "frame " << t << " pixel (" << i % kW << "," << i / kW << ") kernel " << int(k.mask[i]) << " reference "
                            << int(r.mask[i]);
            if (k.mask[i] != r.mask[i]) continue;
            ++st.compared;
            if (r.mask[i] & RRC_MASK_HIT) ++st.hits;
            if (r.mask[i] & RRC_MASK_REFRESHED) ++st.refreshed;
            for (size_t ch = 0; ch < channels.size(); ++ch) {
                const uint32_t m = channels[ch].components;
                const bool fp16 = channels[ch].precision == RRC_HISTORY_FP16;
                const rrc_ref::ChannelResult& rc = r.channels[ch];
                st.rectified += rc.rectified[i];
                if (r.mask[i] & RRC_MASK_REFRESHED) st.rectified_refreshed += rc.rectified[i];
                if (channels[ch].antilag && rc.antilag_c[i] < 1.0) {
                    ++st.shortened;
                    st.dropped += rc.antilag_age[i] == 0;
                }
                st.capped += rc.blur_capped[i];
                st.view_capped += rc.view_capped[i];
                st.max_theta = std::max(st.max_theta, rc.view_theta[i]);
                // alpha / theta sits on a step of its floor within the fp32 error: either age is right.
                if (rc.view_uncertain[i]) {
                    ++st.view_uncertain;
                    continue;
                }
                // n_a sits on a step of floor(c n_prev) within the fp32 error: either age is right.
                if (rc.antilag_uncertain[i]) {
                    ++st.uncertain;
                    continue;
                }
                // B / b sits on a step of its floor within the fp32 error: either age is right.
                if (rc.blur_uncertain[i]) {
                    ++st.blur_uncertain;
                    continue;
                }
                if (k.age[ch][i] != rc.age[i])
                    ages.add() << "frame " << t << " pixel " << i << " channel " << ch << " kernel " << k.age[ch][i] << " reference "
                               << rc.age[i];
                for (uint32_t q = 0; q < m; ++q) {
                    const double kv = k.values[ch][m * i + q], rv = rc.out[m * i + q];
                    const double err = std::fabs(kv - rv);
                    const double tol = value_tolerance(rc, prev, ch, m, i, q, fp16, r, in.desc.prev_jitter);
                    if (!(err <= tol))
                        values.add() << "frame " << t << " pixel (" << i % kW << "," << i / kW << ") channel " << ch << " component " << q
                                     << " kernel " << kv << " reference " << rv << " rectified " << int(rc.rectified[i]);
                    if (fp16)
                        st.max_fp16_steps = std::max(st.max_fp16_steps, err / fp16_step(rc.exact[m * i + q]));
                    else
                        st.max_fp32_err = std::max(st.max_fp32_err, err);
                }
                if (channels[ch].confidence) {
                    const double err = std::fabs(k.weight[ch][i] - rc.weight[i]);
                    if (!(err <= 1e-6 + 1e-5 * std::fabs(rc.weight[i])))
                        weights.add() << "frame " << t << " pixel " << i << " kernel " << k.weight[ch][i] << " reference " << rc.weight[i];
                }
            }
            // Would the comparison have caught each wrong variant here?
            for (size_t mu = 0; mu < mutants.size(); ++mu) {
                const size_t ch = mutants[mu].channel;
                const uint32_t m = channels[ch].components;
                const bool fp16 = channels[ch].precision == RRC_HISTORY_FP16;
                bool caught = mr[mu].mask[i] != r.mask[i];
                for (uint32_t q = 0; q < m && !caught; ++q) {
                    const double tol = value_tolerance(r.channels[ch], prev, ch, m, i, q, fp16, r, in.desc.prev_jitter);
                    caught = std::fabs(mr[mu].channels[ch].out[m * i + q] - r.channels[ch].out[m * i + q]) > 2 * tol;
                }
                st.caught[mu] += caught;
            }
            for (size_t ch = 0; ch < channels.size() && lighting_turn > 0.0f; ++ch) {
                const uint32_t m = channels[ch].components;
                const bool fp16 = channels[ch].precision == RRC_HISTORY_FP16;
                bool caught = false;
                for (uint32_t q = 0; q < m && !caught; ++q) {
                    const double tol = value_tolerance(r.channels[ch], prev, ch, m, i, q, fp16, r, in.desc.prev_jitter);
                    caught = std::fabs(r_still.channels[ch].out[m * i + q] - r.channels[ch].out[m * i + q]) > 2 * tol;
                }
                st.turn_caught += caught;
            }
        }
        prev = kernel_state(in.frame.depth, k);
    }
    std::printf(
        "%-24s compared %lld skipped %lld hits %lld refreshed %lld rectified %lld (refreshed %lld) max fp32 err %.3g max fp16 steps %.3g\n"
        "%-24s antilag: shortened %lld dropped %lld uncertain %lld; blur bound: capped %lld uncertain %lld; view lobe: capped %lld "
        "uncertain %lld max theta %.3g\n",
        name, (long long)st.compared, (long long)st.skipped, (long long)st.hits, (long long)st.refreshed, (long long)st.rectified,
        (long long)st.rectified_refreshed, st.max_fp32_err, st.max_fp16_steps, "", (long long)st.shortened, (long long)st.dropped,
        (long long)st.uncertain, (long long)st.capped, (long long)st.blur_uncertain, (long long)st.view_capped,
        (long long)st.view_uncertain, st.max_theta);
    EXPECT_LE(st.uncertain, st.shortened / 20 + 5) << name << ": too many pixels with an uncertain lag-detector age";
    EXPECT_LE(st.blur_uncertain, st.capped / 20 + 5) << name << ": too many pixels with an uncertain blur-bound age";
    EXPECT_LE(st.view_uncertain, st.view_capped / 20 + 5) << name << ": too many pixels with an uncertain view-lobe age";
    if (lighting_turn > 0.0f)
        std::printf("  wrong variant %-32s would fail on %lld values\n", "the lighting's turn ignored", (long long)st.turn_caught);
    EXPECT_GT(st.compared, (int64_t)n * kFrames * 9 / 10) << name << ": too few pixels compared";
    EXPECT_GT(st.hits + st.refreshed, (int64_t)n * kFrames / 3) << name << ": too few hits";
    for (size_t mu = 0; mu < mutants.size(); ++mu) {
        std::printf("  wrong variant %-32s would fail on %lld values\n", mutants[mu].name.c_str(), (long long)st.caught[mu]);
        EXPECT_GE(st.caught[mu], kMinCaught) << name << ": the comparison would not notice " << mutants[mu].name;
    }
    return st;
}

rrc_channel_desc rectified(rrc_channel_desc d, float gamma) {
    d.rectify = 1;
    d.rectify_gamma = gamma;
    return d;
}

rrc_channel_desc gaussian(rrc_channel_desc d, float sigma) {
    d.filter = RRC_HISTORY_FILTER_GAUSSIAN;
    d.blur_sigma = sigma;
    return d;
}

const auto kFp16 = RRC_HISTORY_FP16, kFp32 = RRC_HISTORY_FP32;
const auto kBil = RRC_HISTORY_FILTER_BILINEAR;

// ---- Rectification ----------------------------------------------------------------

class Rectify : public ::testing::TestWithParam<float> {};

TEST_P(Rectify, MatchesTheReference) {
    const float gamma = GetParam();
    const float other = gamma == 1.0f ? 2.5f : 1.0f;
    const float asked = gamma == 1.0f ? 0.0f : gamma;  // gamma 1 as the default (0)
    const std::vector<rrc_channel_desc> chs = {
        rectified(channel("r1h", 1, 0.8f, kFp16, RRC_BLEND_FIXED, kBil), asked),
        rectified(channel("r1f", 1, 0.8f, kFp32, RRC_BLEND_AGE_AWARE, kBil, 0, 1), asked),  // with confidence
        rectified(channel("r4h", 4, 0.0f, kFp16, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_CATMULL_ROM, 16), asked),
        rectified(channel("r4f", 4, 0.9f, kFp32, RRC_BLEND_FIXED, kBil), asked),
    };
    std::vector<Mutant> mutants;
    for (size_t c = 0; c < chs.size(); ++c) {
        mutants.push_back({std::string(chs[c].name) + " without rectify", c, [](rrc_channel_desc& d) { d.rectify = 0; }});
        mutants.push_back(
            {std::string(chs[c].name) + " gamma " + std::to_string(other), c, [other](rrc_channel_desc& d) { d.rectify_gamma = other; }});
    }
    const std::string name = "rectify_gamma_" + std::to_string(gamma);
    CaseStats st = run_accumulating(name.c_str(), chs, mutants, true);
    EXPECT_GT(st.rectified, 300) << "rectification hardly moved any history";
}

INSTANTIATE_TEST_SUITE_P(Gamma, Rectify, ::testing::Values(1.0f, 2.5f),
                         [](const ::testing::TestParamInfo<float>& i) { return i.param == 1.0f ? "gamma_1" : "gamma_2_5"; });

// ---- The Gaussian history filter --------------------------------------------------

class Gaussian : public ::testing::TestWithParam<float> {};

TEST_P(Gaussian, MatchesTheReference) {
    const float sigma = GetParam();  // 0: the default 0.5
    const float other = sigma == 0.0f ? 0.8f : 0.5f;
    const std::vector<rrc_channel_desc> chs = {
        gaussian(channel("g1h", 1, 0.6f, kFp16, RRC_BLEND_FIXED, kBil), sigma),
        gaussian(channel("g1f", 1, 0.8f, kFp32, RRC_BLEND_AGE_AWARE, kBil, 0, 1), sigma),  // with confidence
        gaussian(channel("g4h", 4, 0.6f, kFp16, RRC_BLEND_FIXED, kBil, 0, 1), sigma),      // fp16 with confidence
        gaussian(channel("g4f", 4, 0.0f, kFp32, RRC_BLEND_RUNNING_MEAN, kBil, 32), sigma),
    };
    std::vector<Mutant> mutants;
    for (size_t c = 0; c < chs.size(); ++c) {
        mutants.push_back({std::string(chs[c].name) + " bilinear (no blur)", c, [](rrc_channel_desc& d) {
                               d.filter = RRC_HISTORY_FILTER_BILINEAR;
                               d.blur_sigma = 0.0f;
                           }});
        mutants.push_back(
            {std::string(chs[c].name) + " sigma " + std::to_string(other), c, [other](rrc_channel_desc& d) { d.blur_sigma = other; }});
    }
    const std::string name = "gaussian_sigma_" + std::to_string(sigma == 0.0f ? 0.5f : sigma);
    run_accumulating(name.c_str(), chs, mutants, false);
}

INSTANTIATE_TEST_SUITE_P(Sigma, Gaussian, ::testing::Values(0.0f, 0.8f),
                         [](const ::testing::TestParamInfo<float>& i) { return i.param == 0.0f ? "default" : "sigma_0_8"; });

// Rectification and the blur together on one channel.
TEST(RectifyGaussian, MatchesTheReference) {
    const std::vector<rrc_channel_desc> chs = {rectified(gaussian(channel("rg", 4, 0.8f, kFp16, RRC_BLEND_FIXED, kBil), 0.7f), 2.5f)};
    const std::vector<Mutant> mutants = {{"rg without rectify", 0, [](rrc_channel_desc& d) { d.rectify = 0; }},
                                         {"rg bilinear", 0, [](rrc_channel_desc& d) {
                                              d.filter = RRC_HISTORY_FILTER_BILINEAR;
                                              d.blur_sigma = 0.0f;
                                          }}};
    run_accumulating("rectify_gaussian", chs, mutants, true);
}

// Rectification applies on REFRESHED pixels too (a hit for accumulating
// channels), next to a REUSE channel that refreshes under a TILED policy.
TEST(RectifyRefreshed, MatchesTheReference) {
    const std::vector<rrc_channel_desc> chs = {channel("shade", 4, 0.0f, kFp16, RRC_BLEND_REUSE, kBil),
                                               rectified(channel("pcf", 1, 0.8f, kFp32, RRC_BLEND_FIXED, kBil), 1.5f)};
    const std::vector<Mutant> mutants = {{"pcf without rectify", 1, [](rrc_channel_desc& d) { d.rectify = 0; }}};
    const Policy tiled{"tiled_4", RRC_REFRESH_TILED, 4, 2, 2, 0};
    CaseStats st = run_accumulating("rectify_refreshed", chs, mutants, true, &tiled);
    EXPECT_GT(st.refreshed, 1000) << "too few refreshed pixels";
    EXPECT_GT(st.rectified_refreshed, 50) << "too few refreshed pixels rectified";
}

// ---- The lag detector ---------------------------------------------------------------

rrc_channel_desc antilagged(rrc_channel_desc d, float gamma, float threshold) {
    d.antilag = 1;
    d.antilag_gamma = gamma;
    d.antilag_threshold = threshold;
    return d;
}

class Antilag : public ::testing::TestWithParam<float> {};

// The brightening front leaves the history outside its box behind it: the
// detector shortens (and drops) ages there, and the kernel's ages and values
// must match the reference's, each blend mode, 1 and 4 components, fp16 and
// fp32, with confidence, with and without rectification.
TEST_P(Antilag, MatchesTheReference) {
    const float threshold = GetParam();
    const std::vector<rrc_channel_desc> chs = {
        antilagged(channel("a1h", 1, 0.8f, kFp16, RRC_BLEND_AGE_AWARE, kBil), 1.0f, threshold),
        // With confidence, the default gamma (a wide box: half the threshold keeps it noticeable).
        antilagged(channel("a1f", 1, 0.9f, kFp32, RRC_BLEND_FIXED, kBil, 0, 1), 0.0f, 0.5f * threshold),
        antilagged(rectified(channel("a4h", 4, 0.0f, kFp16, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_CATMULL_ROM, 16), 1.0f), 1.5f,
                   threshold),
        antilagged(channel("a4f", 4, 0.9f, kFp32, RRC_BLEND_AGE_AWARE, kBil), 3.0f, threshold),
    };
    std::vector<Mutant> mutants;
    for (size_t c = 0; c < chs.size(); ++c) {
        mutants.push_back({std::string(chs[c].name) + " without antilag", c, [](rrc_channel_desc& d) {
                               d.antilag = 0, d.antilag_gamma = 0, d.antilag_threshold = 0;
                           }});
    }
    mutants.push_back({"a1h other threshold", 0, [threshold](rrc_channel_desc& d) { d.antilag_threshold = threshold * 2.0f; }});
    mutants.push_back({"a4f other gamma", 3, [](rrc_channel_desc& d) { d.antilag_gamma = 0.5f; }});
    const std::string name = "antilag_threshold_" + std::to_string(threshold);
    CaseStats st = run_accumulating(name.c_str(), chs, mutants, true);
    EXPECT_GT(st.shortened, 300) << "the lag detector hardly shortened any history";
    EXPECT_GT(st.dropped, 100) << "the lag detector hardly dropped any history";
}
INSTANTIATE_TEST_SUITE_P(Threshold, Antilag, ::testing::Values(0.25f, 0.5f),
                         [](const ::testing::TestParamInfo<float>& i) { return i.param == 0.25f ? std::string("t0_25") : std::string("t0_5"); });

// ---- The blur bound ----------------------------------------------------------------

rrc_channel_desc blur_bounded(rrc_channel_desc d, float B) {
    d.blur_bound = B;
    return d;
}

class BlurBound : public ::testing::TestWithParam<float> {};

// The jittered, moving scene fetches history at fractions all over (0, 1): the
// bound caps ages wherever B / b is below them, and the kernel's ages and values
// must match the reference's, each blend mode, 1 and 4 components, fp16 and fp32,
// BILINEAR and GAUSSIAN, with confidence, with the lag detector and rectification.
TEST_P(BlurBound, MatchesTheReference) {
    const float B = GetParam();
    const std::vector<rrc_channel_desc> chs = {
        blur_bounded(channel("b1h", 1, 0.9f, kFp16, RRC_BLEND_AGE_AWARE, kBil), B),
        blur_bounded(channel("b1f", 1, 0.9f, kFp32, RRC_BLEND_FIXED, kBil, 0, 1), B),  // with confidence
        blur_bounded(antilagged(rectified(gaussian(channel("b4h", 4, 0.0f, kFp16, RRC_BLEND_RUNNING_MEAN, kBil, 16), 0.0f), 1.0f), 1.5f, 0.25f),
                     B),
        blur_bounded(antilagged(channel("b4f", 4, 0.9f, kFp32, RRC_BLEND_AGE_AWARE, kBil), 3.0f, 0.25f), B),
    };
    std::vector<Mutant> mutants;
    for (size_t c = 0; c < chs.size(); ++c)
        mutants.push_back({std::string(chs[c].name) + " without the bound", c, [](rrc_channel_desc& d) { d.blur_bound = 0.0f; }});
    mutants.push_back({"b1h half the bound", 0, [B](rrc_channel_desc& d) { d.blur_bound = 0.5f * B; }});
    const std::string name = "blur_bound_" + std::to_string(B);
    CaseStats st = run_accumulating(name.c_str(), chs, mutants, true);
    EXPECT_GT(st.capped, 300) << "the blur bound hardly capped any history";
}
INSTANTIATE_TEST_SUITE_P(Bound, BlurBound, ::testing::Values(0.5f, 1.0f),
                         [](const ::testing::TestParamInfo<float>& i) { return i.param == 0.5f ? std::string("b0_5") : std::string("b1"); });

// ---- The view-dependent history ------------------------------------------------------

rrc_channel_desc lobed(rrc_channel_desc d, float alpha) {
    d.view_lobe = alpha;
    return d;
}

class ViewLobeKernel : public ::testing::TestWithParam<float> {};

// The orbiting camera turns the view direction to every surface point by a
// different angle each frame (nearer points turn more): the lobe caps ages
// wherever alpha / theta is below them, and the kernel's ages and values must
// match the reference's, each blend mode, 1 and 4 components, fp16 and fp32,
// with confidence, with the lag detector and the blur bound beside it.
TEST_P(ViewLobeKernel, MatchesTheReference) {
    const float alpha = GetParam();
    const std::vector<rrc_channel_desc> chs = {
        lobed(channel("v1h", 1, 0.9f, kFp16, RRC_BLEND_AGE_AWARE, kBil), alpha),
        lobed(channel("v1f", 1, 0.9f, kFp32, RRC_BLEND_FIXED, kBil, 0, 1), alpha),  // with confidence
        lobed(antilagged(channel("v4h", 4, 0.0f, kFp16, RRC_BLEND_RUNNING_MEAN, kBil, 16), 1.5f, 0.25f), alpha),
        lobed(blur_bounded(channel("v4f", 4, 0.9f, kFp32, RRC_BLEND_AGE_AWARE, kBil), 1.0f), alpha),
    };
    std::vector<Mutant> mutants;
    for (size_t c = 0; c < chs.size(); ++c)
        mutants.push_back({std::string(chs[c].name) + " without the lobe", c, [](rrc_channel_desc& d) { d.view_lobe = 0.0f; }});
    mutants.push_back({"v1h half the lobe", 0, [alpha](rrc_channel_desc& d) { d.view_lobe = 0.5f * alpha; }});
    const std::string name = "view_lobe_" + std::to_string(alpha);
    CaseStats st = run_accumulating(name.c_str(), chs, mutants, true, nullptr, /*camera_positions=*/true);
    EXPECT_GT(st.view_capped, 300) << "the view lobe hardly capped any history";
}
INSTANTIATE_TEST_SUITE_P(Lobe, ViewLobeKernel, ::testing::Values(0.01f, 0.04f),
                         [](const ::testing::TestParamInfo<float>& i) { return i.param == 0.01f ? std::string("a0_01") : std::string("a0_04"); });

// The lighting's turn phi (0.8) adds to every pixel's view turn (docs/CONVENTIONS.md,
// "The view-dependent history"): phi of the scene's largest view turns, varied per
// frame, so that caps move at every pixel; a variant that ignores phi must be caught.
TEST(ViewLobeKernelTurn, TheLightingsTurnAddsToTheViewTurn) {
    const float alpha = 0.04f, phi = 0.015f;
    const std::vector<rrc_channel_desc> chs = {
        lobed(channel("t1h", 1, 0.9f, kFp16, RRC_BLEND_AGE_AWARE, kBil), alpha),
        lobed(channel("t4f", 4, 0.9f, kFp32, RRC_BLEND_FIXED, kBil), alpha),
    };
    CaseStats st = run_accumulating("lighting_turn", chs, {}, true, nullptr, /*camera_positions=*/true, phi);
    EXPECT_GT(st.view_capped, 300) << "the view lobe hardly capped any history";
    EXPECT_GT(st.turn_caught, 300) << "ignoring the lighting's turn changed too few values to be tested";
}

// ---- The spatial fill -------------------------------------------------------------

struct FillMutant {
    std::string name;
    size_t channel;
    std::function<void(rrc_channel_desc&)> change;
    bool fade;
};

class Fill : public ::testing::TestWithParam<rrc_depth_mode> {};

TEST_P(Fill, DisplaysTheFillOfTheUnfilledHistory) {
    const rrc_depth_mode mode = GetParam();
    const std::vector<rrc_channel_desc> chs = {
        filled(channel("mean1", 1, 0.0f, kFp32, RRC_BLEND_RUNNING_MEAN, kBil), 4, 1, 0.0f),
        // The blur bound keeps capped pixels young; the fill must stay display-only there too.
        blur_bounded(filled(channel("mean4", 4, 0.0f, kFp16, RRC_BLEND_RUNNING_MEAN, kBil, 16), 8, 2, 4.0f), 0.5f),
        filled(channel("reuse1", 1, 0.0f, kFp16, RRC_BLEND_REUSE, kBil), 8, 1, 4.0f),
        filled(channel("reuse4", 4, 0.0f, kFp32, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_NEAREST), 4, 2, 0.0f),
    };
    std::vector<rrc_channel_desc> twin_chs;
    for (const rrc_channel_desc& d : chs) twin_chs.push_back(without_fill(d));
    std::vector<FillMutant> mutants;
    for (size_t c = 0; c < chs.size(); ++c) {
        const std::string n = chs[c].name;
        mutants.push_back({n + " without the fade", c, [](rrc_channel_desc&) {}, false});
        const uint32_t other_r = chs[c].fill_radius == 1 ? 2 : 1;
        mutants.push_back({n + " radius " + std::to_string(other_r), c, [other_r](rrc_channel_desc& d) { d.fill_radius = other_r; }, true});
        mutants.push_back({n + " depth test ignored", c, [](rrc_channel_desc& d) { d.fill_depth_tolerance = 1e30f; }, true});
        if (chs[c].fill_prior > 0) mutants.push_back({n + " fallback ignored", c, [](rrc_channel_desc& d) { d.fill_prior = 0.0f; }, true});
    }

    // Invalid samples leave empty histories (age 0) to fill from the neighbours alone.
    rrc_scene::Scene scene(scene_of(mode, 0.02));
    const rrc_reprojection source = RRC_REPROJECTION_PREV_CLIP;
    Context ctx(scene_context_desc(scene.config(), source, chs));
    Context twin(scene_context_desc(scene.config(), source, twin_chs));
    ASSERT_TRUE(ctx && twin);
    const std::string name = std::string("fill_") + (mode == RRC_DEPTH_MODE_STANDARD   ? "standard"
                                                     : mode == RRC_DEPTH_MODE_REVERSED ? "reversed"
                                                                                       : "linear");

    Mismatches masks(name + " mask (fill vs twin)"), ages(name + " age (fill vs twin)"),
        unfilled(name + " value of a pixel not filled (fill vs twin)"), values(name + " displayed value");
    const size_t n = (size_t)kW * kH;
    int64_t compared = 0, skipped = 0, with_neighbours = 0, empty_filled = 0, with_fallback = 0;
    double max_err = 0, max_ratio = 0;  // the largest error, and the largest error / tolerance
    std::vector<int64_t> filled_count(chs.size(), 0), caught(mutants.size(), 0);
    for (int t = 0; t < kFrames; ++t) {
        SceneFrameInputs in;
        in.frame = scene.render(t);
        make_frame_inputs(in, source, chs);
        // The fallback: the noise-free truth, with a few non-finite pixels (not used there).
        std::vector<std::vector<float>> fallback(chs.size());
        for (size_t c = 0; c < chs.size(); ++c) {
            fallback[c] = chs[c].components == 1 ? in.frame.truth1 : in.frame.truth4;
            for (size_t p = 0; p < n; p += 29) fallback[c][chs[c].components * p] = NAN;
            in.inputs[c].fallback = fallback[c].data();
        }
        FrameResult k = ctx.run(in.desc);
        FrameResult tw = twin.run(in.desc);  // ignores the fallback

        std::vector<rrc_context_desc> mutant_desc(mutants.size(), ctx.desc());
        std::vector<std::vector<rrc_channel_desc>> mutant_channels(mutants.size(), chs);
        for (size_t c = 0; c < chs.size(); ++c) {
            const rrc_ref::FillInputs fin{tw.values[c].data(), tw.age[c].data(), in.frame.depth.data(), fallback[c].data()};
            const rrc_ref::FillResult ref = rrc_ref::spatial_fill(ctx.desc(), c, fin);
            std::vector<rrc_ref::FillResult> mref(mutants.size());
            for (size_t mu = 0; mu < mutants.size(); ++mu) {
                if (mutants[mu].channel != c) continue;
                mutants[mu].change(mutant_channels[mu][c]);
                mutant_desc[mu].channels = mutant_channels[mu].data();
                rrc_ref::FillOptions o;
                o.fade = mutants[mu].fade;
                mref[mu] = rrc_ref::spatial_fill(mutant_desc[mu], c, fin, o);
            }
            const uint32_t m = chs[c].components;
            const bool fp16 = false;  // displayed values are read back in fp32, fp16 channels' too
            for (size_t i = 0; i < n; ++i) {
                // The fill is display-only: the history (ages, and the twin's values) is the twin's.
                if (k.age[c][i] != tw.age[c][i])
                    ages.add() << "frame " << t << " pixel " << i << " channel " << c << " fill " << k.age[c][i] << " twin "
                               << tw.age[c][i];
                if (c == 0 && k.mask[i] != tw.mask[i]) masks.add() << "frame " << t << " pixel " << i;
                if (!ref.filled[i]) {
                    for (uint32_t q = 0; q < m; ++q)
                        if (k.values[c][m * i + q] != tw.values[c][m * i + q])
                            unfilled.add() << "frame " << t << " pixel " << i << " channel " << c << " fill " << k.values[c][m * i + q]
                                           << " twin " << tw.values[c][m * i + q] << " age " << tw.age[c][i];
                    continue;
                }
                ++filled_count[c];
                if (ref.near_threshold[i]) {
                    ++skipped;
                    continue;
                }
                ++compared;
                with_neighbours += ref.neighbours[i] > 0;
                empty_filled += tw.age[c][i] == 0 && ref.neighbours[i] > 0;
                with_fallback += chs[c].fill_prior > 0 && std::isfinite(fallback[c][m * i]);
                for (uint32_t q = 0; q < m; ++q) {
                    const size_t e = m * i + q;
                    const double kv = k.values[c][e], rv = ref.shown[e];
                    const double tol = arithmetic_tolerance(rv, ref.exact[e], fp16) + ref.err[e];
                    const double err = std::fabs(kv - rv);
                    if (!(err <= tol))
                        values.add() << "frame " << t << " pixel (" << i % kW << "," << i / kW << ") channel " << c << " component " << q
                                     << " kernel " << kv << " reference " << rv << " history " << tw.values[c][e] << " age " << tw.age[c][i]
                                     << " neighbours " << int(ref.neighbours[i]);
                    max_err = std::max(max_err, err);
                    max_ratio = std::max(max_ratio, err / tol);
                }
                for (size_t mu = 0; mu < mutants.size(); ++mu) {
                    if (mutants[mu].channel != c || mref[mu].near_threshold[i]) continue;
                    bool differs = false;
                    for (uint32_t q = 0; q < m && !differs; ++q) {
                        const size_t e = m * i + q;
                        const double tol = arithmetic_tolerance(ref.shown[e], ref.exact[e], fp16) + ref.err[e];
                        differs = std::fabs(mref[mu].shown[e] - ref.shown[e]) > 2 * tol;
                    }
                    caught[mu] += differs;
                }
            }
        }
    }
    std::printf(
        "%-16s filled compared %lld skipped (depth test near tau) %lld with neighbours %lld empty %lld with fallback %lld max err "
        "%.3g (%.3g of the tolerance)\n",
        name.c_str(), (long long)compared, (long long)skipped, (long long)with_neighbours, (long long)empty_filled,
        (long long)with_fallback, max_err, max_ratio);
    for (size_t c = 0; c < chs.size(); ++c) EXPECT_GT(filled_count[c], 500) << name << " channel " << c << ": too few filled pixels";
    EXPECT_GT(with_neighbours, 2000) << name;
    EXPECT_GT(empty_filled, 20) << name << ": too few empty histories filled";
    EXPECT_GT(with_fallback, 500) << name;
    EXPECT_LT(skipped, compared / 50) << name << ": too many pixels near the depth threshold";
    for (size_t mu = 0; mu < mutants.size(); ++mu) {
        std::printf("  wrong variant %-28s would fail on %lld pixels\n", mutants[mu].name.c_str(), (long long)caught[mu]);
        EXPECT_GE(caught[mu], kMinCaught) << name << ": the comparison would not notice " << mutants[mu].name;
    }
}

INSTANTIATE_TEST_SUITE_P(DepthModes, Fill, ::testing::Values(RRC_DEPTH_MODE_REVERSED, RRC_DEPTH_MODE_STANDARD, RRC_DEPTH_MODE_LINEAR),
                         [](const ::testing::TestParamInfo<rrc_depth_mode>& i) {
                             return i.param == RRC_DEPTH_MODE_STANDARD   ? "standard"
                                    : i.param == RRC_DEPTH_MODE_REVERSED ? "reversed"
                                                                         : "linear";
                         });

}  // namespace

// ---- Edge cases the conventions decide, on a small static frame -------------------

namespace edge {

// An 8x8 static frame seen by an identity CAMERA (every pixel a hit from the
// second frame on), STANDARD depth 0.5.
rrc_ref_test::Scene static_frame() {
    rrc_ref_test::Scene s(8, 8, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_CAMERA);
    s.ctx.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    return s;
}

}  // namespace edge

// "Rectification": only the blend formula uses the clamped H; W' below 2^-126
// (confidence) keeps the resampled H.  Frame 0 leaves W = 0 (confidence 0) at
// age 1; frame 1's hits with confidence 0 keep H = 5, though the 9 equal
// samples' box is {1}.
TEST(FinishingEdge, RectifiedPixelWhoseWeightUnderflowsKeepsTheResampledHistory) {
    rrc_ref_test::Scene s = edge::static_frame();
    const int c = s.add_channel(1, 0.5f, RRC_BLEND_FIXED, kBil, kFp32, true);
    s.channel_descs[c].rectify = 1;
    for (float& v : s.samples[c]) v = 5.0f;
    s.confidence[c].assign(s.size(), 0.0f);
    s.desc();
    Context ctx(s.ctx);
    ASSERT_TRUE(ctx);
    FrameResult k0 = ctx.run(s.desc());
    rrc_ref::PreviousFrame prev = rrc_ref::as_previous(s.ctx, s.frame, rrc_ref::run_frame(s.ctx, {}, s.frame));
    for (float& v : s.samples[c]) v = 1.0f;
    FrameResult k1 = ctx.run(s.desc());
    rrc_ref::FrameResult r1 = rrc_ref::run_frame(s.ctx, prev, s.frame);
    EXPECT_EQ(k0.values[c], std::vector<float>(s.size(), 5.0f));
    for (size_t i = 0; i < s.size(); ++i) {
        ASSERT_EQ(r1.mask[i], RRC_MASK_HIT);
        ASSERT_EQ(r1.channels[c].out[i], 5.0);  // the resampled H
        EXPECT_EQ(k1.values[c][i], 5.0f) << "pixel " << i;
        EXPECT_EQ(k1.age[c][i], 1) << "pixel " << i;
        EXPECT_EQ(k1.weight[c][i], 0.0f) << "pixel " << i;
    }
    // With a confidence the blend happens and uses the clamped H = 1.
    s.confidence[c].assign(s.size(), 1.0f);
    FrameResult k2 = ctx.run(s.desc());
    for (size_t i = 0; i < s.size(); ++i) EXPECT_EQ(k2.values[c][i], 1.0f) << "pixel " << i;
}

// "The spatial fill": p is filled when it is not background and n_p < T.  A
// pixel of invalid geometry (non-finite depth) is not background: its proxy
// is NaN, so no neighbour counts, but the fallback does.  Its neighbours skip it.
TEST(FinishingEdge, InvalidGeometryPixelIsFilledFromTheFallback) {
    rrc_ref_test::Scene s = edge::static_frame();
    const int c = s.add_channel(1, 0.0f, RRC_BLEND_RUNNING_MEAN, kBil, kFp32);
    s.channel_descs[c].fill_age = 4;
    s.channel_descs[c].fill_radius = 1;
    s.channel_descs[c].fill_prior = 4.0f;
    for (float& v : s.samples[c]) v = 2.0f;
    const size_t bad = s.at(3, 3);
    s.depth[bad] = NAN;
    std::vector<float> fallback(s.size(), 7.0f);
    s.desc();
    Context ctx(s.ctx);
    ASSERT_TRUE(ctx);
    s.inputs[c].fallback = fallback.data();
    FrameResult k = ctx.run(s.frame);
    rrc_ref::FrameResult r = rrc_ref::run_frame(s.ctx, {}, s.frame);
    ASSERT_EQ(r.mask[bad], RRC_MASK_INVALID_GEOMETRY);
    ASSERT_EQ(r.channels[c].age[bad], 1);
    EXPECT_DOUBLE_EQ(r.channels[c].shown[bad], (1 * 2.0 + 0.75 * 4 * 7.0) / (1 + 0.75 * 4));  // 23/4
    // A neighbour of it: 7 of its 8 neighbours (weight 1 each, value 2) and the fallback.
    EXPECT_DOUBLE_EQ(r.channels[c].shown[s.at(4, 4)], (2.0 + 0.75 * (7 * 2.0 + 4 * 7.0)) / (1 + 0.75 * 11));
    for (size_t i = 0; i < s.size(); ++i)
        EXPECT_NEAR(k.values[c][i], r.channels[c].shown[i], 1e-6 + 1e-5 * std::fabs(r.channels[c].shown[i]))
            << "pixel (" << i % s.W << "," << i / s.W << ") mask " << int(r.mask[i]);
}

// The fill after the split path: rrc_frame_classify + rrc_frame_resolve (the
// REUSE samples NaN outside the listed quads) give the fused frame's bits,
// displayed values included.
// Run plain and with the residual (0.9) on the accumulating channel, whose base
// resolve reads with its samples (docs/CONVENTIONS.md, "The residual").
class FillSplit : public ::testing::TestWithParam<bool> {};

TEST_P(FillSplit, ClassifyResolveGivesTheFusedBits) {
    std::vector<rrc_channel_desc> chs = {filled(channel("shade", 4, 0.0f, kFp16, RRC_BLEND_REUSE, kBil), 8, 2, 4.0f),
                                         filled(channel("mean", 1, 0.0f, kFp32, RRC_BLEND_RUNNING_MEAN, kBil), 4, 1, 0.0f)};
    chs[1].residual = GetParam() ? 1u : 0u;
    rrc_scene::Scene scene(scene_of(RRC_DEPTH_MODE_REVERSED, 0.01));
    const rrc_reprojection source = RRC_REPROJECTION_PREV_CLIP;
    rrc_context_desc desc = scene_context_desc(scene.config(), source, chs);
    apply(Policy{"tiled_4", RRC_REFRESH_TILED, 4, 2, 2, 0}, desc);
    Context fused(desc), split(desc);
    ASSERT_TRUE(fused && split);
    const size_t n = (size_t)kW * kH;
    int64_t listed = 0, young = 0;
    for (int t = 0; t < kFrames; ++t) {
        SceneFrameInputs in;
        in.frame = scene.render(t);
        make_frame_inputs(in, source, chs);
        const std::vector<float>& fallback = in.frame.truth4;
        in.inputs[0].fallback = fallback.data();
        std::vector<float> base(in.frame.truth1.size());  // the residual's: a biased, noise-free estimate
        for (size_t i = 0; i < base.size(); ++i) base[i] = 0.5f * in.frame.truth1[i] + 0.25f;
        in.inputs[1].fallback = base.data();  // without the residual: ignored
        FrameResult a = fused.run(in.desc);

        Classification cl(kW, kH);
        ASSERT_EQ(cl.run(split.get(), geometry_of(in.desc)), RRC_SUCCESS) << rrc_last_error();
        listed += cl.out.quad_count;
        // The fallback stays on the REUSE channel's input (in.inputs[0]).
        HostSamples host(chs, in.desc, cl.listed(), kW, kH);
        FrameResult b;
        BoundOutput o(b, chs, n);
        ASSERT_EQ(rrc_frame_resolve(split.get(), &host.desc, &o.frame), RRC_SUCCESS) << rrc_last_error();
        EXPECT_EQ(b.mask, a.mask) << "frame " << t;
        for (size_t c = 0; c < 2; ++c) {
            EXPECT_EQ(b.age[c], a.age[c]) << "frame " << t << " channel " << c;
            EXPECT_EQ(b.values[c], a.values[c]) << "frame " << t << " channel " << c;
            for (size_t i = 0; i < n; ++i) young += a.age[c][i] < chs[c].fill_age && b.values[c][i * chs[c].components] != 0.0f;
        }
    }
    EXPECT_GT(listed, 0);
    EXPECT_GT(young, (int64_t)n) << "too few young pixels compared";
}

INSTANTIATE_TEST_SUITE_P(Residual, FillSplit, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& i) { return i.param ? "Residual" : "Plain"; });

// The fill of a view reads that view's own frame: two views interleaved in one
// context give each view's bits of a one-view context that sees only its frames.
TEST(FillViews, EachViewFillsFromItsOwnFrame) {
    const std::vector<rrc_channel_desc> chs = {filled(channel("mean", 4, 0.0f, kFp16, RRC_BLEND_RUNNING_MEAN, kBil, 16), 8, 2, 4.0f),
                                               filled(channel("pcf", 1, 0.6f, kFp32, RRC_BLEND_FIXED, kBil), 4, 1, 0.0f)};
    rrc_scene::SceneConfig ca = scene_of(RRC_DEPTH_MODE_REVERSED, 0.01), cb = ca;
    cb.seed = 7;
    cb.camera_speed = 1.7;
    const rrc_scene::Scene sa(ca), sb(cb);
    const rrc_reprojection source = RRC_REPROJECTION_PREV_CLIP;
    rrc_context_desc d2 = scene_context_desc(ca, source, chs);
    d2.view_count = 2;
    Context both(d2), only_a(scene_context_desc(ca, source, chs)), only_b(scene_context_desc(cb, source, chs));
    ASSERT_TRUE(both && only_a && only_b);
    for (int t = 0; t < 4; ++t) {
        for (int v = 0; v < 2; ++v) {
            SceneFrameInputs in;
            in.frame = (v == 0 ? sa : sb).render(t);
            make_frame_inputs(in, source, chs);
            in.inputs[0].fallback = in.frame.truth4.data();
            FrameResult one = (v == 0 ? only_a : only_b).run(in.desc);
            in.desc.view = (uint32_t)v;
            FrameResult two = both.run(in.desc);
            EXPECT_EQ(two.mask, one.mask) << "frame " << t << " view " << v;
            for (size_t c = 0; c < chs.size(); ++c) {
                EXPECT_EQ(two.age[c], one.age[c]) << "frame " << t << " view " << v << " channel " << c;
                EXPECT_EQ(two.values[c], one.values[c]) << "frame " << t << " view " << v << " channel " << c;
            }
        }
    }
}
