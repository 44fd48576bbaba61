// API 0.9's residual (docs/CONVENTIONS.md, "The residual") on the standalone
// path, under the validation layer, on a moving analytic scene (tests/scenes)
// whose signal changes (a brightening front), with a base b that is a biased,
// noise-free estimate of the signal and is not finite at a few pixels:
//   - against a twin context without the residual fed fl(s - b) (and a
//     fallback of 0 where the fill has a prior): the same masks and ages
//     every frame, and every displayed value the twin's plus b within one
//     fp32 rounding (a b that is not finite adds nothing), so the channel
//     filters exactly the residual: in the blend, in the rectification and
//     lag-detector boxes, in the fill, whose prior is the base;
//   - against the double-precision reference (tests/reference) run from the
//     kernel's own state (a third context without residual or fill, whose
//     history is the residual channel's): every displayed value within the
//     value tolerance of tests/support/tolerance.h;
//   - wrong variants of the reference (the residual off; the base not added
//     back) would fail the comparison on many values.
#include "reference/rrc_reference.h"
#include "support/kernel_state.h"
#include "support/rrc_test_context.h"
#include "support/scene_frames.h"
#include "support/tolerance.h"

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>

using namespace rrc_test;

namespace {

const int kW = 64, kH = 40, kFrames = 6;

// The channels: a packed fp16 scalar with the lag detector and a fill whose
// prior is the base (the soft shadow's settings, docs/guide/integration.md), and an
// fp32 RGBA Catmull-Rom channel, rectified.
std::vector<rrc_channel_desc> residual_channels(bool residual, bool fill) {
    std::vector<rrc_channel_desc> c = {
        channel("soft", 1, 0.8f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR),
        channel("rgba", 4, 0.6f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_CATMULL_ROM),
    };
    c[0].antilag = 1;
    c[0].antilag_gamma = 0.5f;
    c[0].antilag_threshold = 0.25f;
    c[1].rectify = 1;
    if (fill) {
        c[0].fill_age = 4;
        c[0].fill_radius = 1;
        c[0].fill_prior = 4.0f;
    }
    for (rrc_channel_desc& d : c) d.residual = residual ? 1u : 0u;
    return c;
}

rrc_scene::SceneConfig scene_of() {
    rrc_scene::SceneConfig sc = scene_config(kW, kH, RRC_DEPTH_MODE_REVERSED);
    sc.jitter = true;
    sc.object_motion = true;
    sc.invalid_fraction = 0.01;
    return sc;
}

// A brightening front sweeping right by 6 pixels a frame: history behind it lags.
void change_signal(rrc_scene::Frame& f, int t) {
    for (int j = 0; j < f.height; ++j)
        for (int i = 0; i < std::min(6 * t, f.width); ++i) {
            const size_t p = (size_t)j * f.width + i;
            f.signal1[p] += 0.5f;
            for (int k = 0; k < 4; ++k) f.signal4[4 * p + k] += 0.125f * (k + 1);
        }
}

// The base: a biased, noise-free estimate (0.75 truth + 0.1), not finite at every 31st pixel.
std::vector<float> base_of(const std::vector<float>& truth, uint32_t components) {
    std::vector<float> b(truth.size());
    for (size_t e = 0; e < b.size(); ++e) b[e] = 0.75f * truth[e] + 0.1f;
    for (size_t p = 0; p * components < b.size(); p += 31) b[p * components] = (p / 31) % 2 ? NAN : INFINITY;
    return b;
}

bool finite_at(const std::vector<float>& b, uint32_t m, size_t i) {
    for (uint32_t q = 0; q < m; ++q)
        if (!std::isfinite(b[m * i + q])) return false;
    return true;
}

TEST(Residual, FiltersTheResidualAndShowsItPlusTheBase) {
    const std::vector<rrc_channel_desc> chs = residual_channels(true, true), twin_chs = residual_channels(false, true),
                                        plain_chs = residual_channels(false, false);
    rrc_scene::Scene scene(scene_of());
    const rrc_reprojection source = RRC_REPROJECTION_PREV_CLIP;
    Context ctx(scene_context_desc(scene.config(), source, chs));
    Context twin(scene_context_desc(scene.config(), source, twin_chs));
    Context plain(scene_context_desc(scene.config(), source, plain_chs));
    ASSERT_TRUE(ctx && twin && plain);
    std::vector<rrc_channel_desc> off = chs;  // wrong variant: the residual off
    for (rrc_channel_desc& d : off) d.residual = 0;
    rrc_context_desc off_desc = ctx.desc();
    off_desc.channels = off.data();

    const size_t n = (size_t)kW * kH;
    int64_t compared = 0, filled = 0, not_finite = 0, twin_mismatch = 0, ref_mismatch = 0, caught_off = 0, caught_unadded = 0;
    int64_t age_mismatch = 0, mask_mismatch = 0;
    std::string first;
    rrc_ref::PreviousFrame prev;
    for (int t = 0; t < kFrames; ++t) {
        SceneFrameInputs in;
        in.frame = scene.render(t);
        change_signal(in.frame, t);
        make_frame_inputs(in, source, chs);
        const std::vector<float>* truth[2] = {&in.frame.truth1, &in.frame.truth4};
        std::vector<std::vector<float>> base(2), residual(2), zero(2);
        for (size_t c = 0; c < 2; ++c) {
            base[c] = base_of(*truth[c], chs[c].components);
            const float* s = in.inputs[c].samples;
            residual[c].resize(base[c].size());
            for (size_t e = 0; e < base[c].size(); ++e) residual[c][e] = s[e] - base[c][e];  // fp32, as the kernel forms it
            zero[c].assign(base[c].size(), 0.0f);
        }
        // The residual context: samples s, fallback b.
        std::vector<rrc_channel_input> res_in = in.inputs, twin_in = in.inputs;
        for (size_t c = 0; c < 2; ++c) {
            res_in[c].fallback = base[c].data();
            twin_in[c].samples = residual[c].data();
            twin_in[c].fallback = zero[c].data();  // the fill's prior: a residual of 0
        }
        rrc_frame_desc res_desc = in.desc, twin_desc = in.desc;
        res_desc.channels = res_in.data();
        twin_desc.channels = twin_in.data();
        const FrameResult k = ctx.run(res_desc), tw = twin.run(twin_desc), pl = plain.run(twin_desc);
        const rrc_ref::FrameResult r = rrc_ref::run_frame(ctx.desc(), prev, res_desc);
        const rrc_ref::FrameResult r_off = rrc_ref::run_frame(off_desc, prev, res_desc);

        for (size_t i = 0; i < n; ++i) {
            if (k.mask[i] != tw.mask[i]) ++mask_mismatch;
            for (size_t c = 0; c < 2; ++c) {
                const uint32_t m = chs[c].components;
                if (k.age[c][i] != tw.age[c][i]) ++age_mismatch;
                const bool fin = finite_at(base[c], m, i);
                not_finite += !fin;
                filled += c == 0 && tw.age[c][i] < 4;
                for (uint32_t q = 0; q < m; ++q) {
                    // The twin's displayed value plus b, one fp32 rounding.
                    const float kv = k.values[c][m * i + q];
                    const float want = fin ? tw.values[c][m * i + q] + base[c][m * i + q] : tw.values[c][m * i + q];
                    if (!(std::fabs(kv - want) <= 2.0 * FLT_EPSILON * std::fabs(want) + FLT_MIN)) {
                        if (twin_mismatch++ == 0)
                            first = "frame " + std::to_string(t) + " pixel " + std::to_string(i) + " channel " + std::to_string(c) +
                                    " kernel " + std::to_string(kv) + " twin + b " + std::to_string(want);
                    }
                }
                // The reference: skip pixels whose hit decision or nearest texel sits within fp32 error of a threshold.
                if (r.near_threshold[i] || r.near_nearest_edge[i] || r.mask[i] != k.mask[i]) continue;
                if (r.channels[c].antilag_uncertain[i]) continue;  // n_a on a step of its floor: either age is right
                ++compared;
                for (uint32_t q = 0; q < m; ++q) {
                    const double rv = r.channels[c].shown[m * i + q];
                    const double spread =
                        prev.valid ? history_spread(prev.channels[c].history, m, q, kW, kH, r.uv_prev_x[i], r.uv_prev_y[i], in.desc.prev_jitter)
                                   : 0.0;
                    const double tol = arithmetic_tolerance(rv, rv, chs[c].precision == RRC_HISTORY_FP16) +
                                       arithmetic_tolerance(r.channels[c].out[m * i + q], r.channels[c].exact[m * i + q], false) +
                                       position_tolerance(spread, kW, kH) + r.channels[c].rectify_err[m * i + q];
                    if (!(std::fabs(k.values[c][m * i + q] - rv) <= tol)) ++ref_mismatch;
                    const double off_v = r_off.channels[c].shown.empty() ? r_off.channels[c].out[m * i + q] : r_off.channels[c].shown[m * i + q];
                    caught_off += std::fabs(off_v - rv) > 2 * tol;
                    caught_unadded += std::fabs(r.channels[c].out[m * i + q] - rv) > 2 * tol;
                }
            }
        }
        prev = kernel_state(in.frame.depth, pl);  // the residual channels' history: the plain twin's
    }
    std::printf("residual: compared %lld filled %lld not-finite base %lld; wrong variants caught: off %lld, base not added %lld\n",
                (long long)compared, (long long)filled, (long long)not_finite, (long long)caught_off, (long long)caught_unadded);
    EXPECT_EQ(mask_mismatch, 0) << "masks differ from the twin's";
    EXPECT_EQ(age_mismatch, 0) << "ages differ from the twin's";
    EXPECT_EQ(twin_mismatch, 0) << "displayed values are not the twin's plus b; the first: " << first;
    EXPECT_EQ(ref_mismatch, 0) << "displayed values differ from the reference's";
    EXPECT_GT(compared, (int64_t)n * 2 * kFrames * 9 / 10) << "too few values compared";
    EXPECT_GT(filled, (int64_t)n / 2) << "the scene must have young (filled) pixels";
    EXPECT_GT(not_finite, 0) << "the base must be non-finite somewhere";
    EXPECT_GT(caught_off, 1000) << "the comparison would not notice the residual off";
    EXPECT_GT(caught_unadded, 1000) << "the comparison would not notice the base not added back";
}

}  // namespace
