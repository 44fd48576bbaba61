// API 0.12's deviation gate (docs/CONVENTIONS.md, "The deviation gate") against
// the independent double-precision reference (tests/reference/gate.h),
// standalone (rrc_frame_run) under the validation layer, on a finely textured
// plane panned by a sub-pixel step each frame (every bilinear fetch blurs the
// history: the case the gate is for), clean and noisy:
//   - 1 and 4 components, fp16 and fp32, each filter, with rectification and
//     the lag detector, with the blur bound, and a RUNNING_MEAN channel; masks,
//     ages and values compared every frame as tests/kernels/finishing_reference_test.cpp
//     does, one frame at a time from the kernel's history and ages.  The
//     kernel's gate state is not read back, so the reference carries its own
//     from frame to frame (rrc_ref::carry_gate_state) with a bound on the
//     kernel's fp32 difference, and a pixel whose stored age that bound leaves
//     open (gate_uncertain) is compared loosely: skipped, and counted;
//   - the gate must act (many capped ages) and the reference without it must
//     differ from the kernel on many values, so the comparison cannot pass
//     without the gate;
//   - a residual channel equals a twin without the residual fed fl(s - b): the
//     gate's deviation is the residual's;
//   - with a spatial fill ("With a spatial fill"): the displayed value against
//     the reference's fill of a twin context's (the same channels without the
//     fill) history and ages, weighed by the reference's own gate state, as
//     tests/kernels/finishing_reference_test.cpp compares the fill (a pixel
//     whose neighbour test lies within fp32 error of its threshold skipped);
//     the gate must leave neighbours out and the reference's fill without its
//     weighing must differ from the kernel, so the comparison cannot pass
//     without it;
//   - the descriptor checks the section states that the option table's generic
//     test (tests/options) does not: confidence, infinity, the range's end.
#include "reference/finish.h"
#include "reference/rrc_reference.h"
#include "support/fill_channel.h"
#include "support/kernel_state.h"
#include "support/mismatches.h"
#include "support/rrc_test_context.h"
#include "support/tolerance.h"

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>

using namespace rrc_test;

namespace {

const int kW = 64, kH = 48, kFrames = 8;
const double kVx = 0.37, kVy = 0.23;  // the pan, pixels a frame
const double kPi = 3.14159265358979323846;

// The average over [a, a + 1] of sin(2 pi f x + p).
double box_sin(double f, double p, double a) {
    const double w = 2.0 * kPi * f;
    return (std::cos(w * a + p) - std::cos(w * (a + 1.0) + p)) / w;
}

// The plane's texture averaged over pixel (i, j) at frame t, component k
// (each its own phase); `fine` = false leaves the finest terms out (a
// residual's smooth, deterministic base).
double texel(int i, int j, int t, int k, bool fine = true) {
    const double x = i - kVx * t, y = j - kVy * t;
    double v = 0.5 + 0.2 * box_sin(0.09, 0.3 + k, x) * box_sin(0.06, 1.1, y);
    if (fine) v += 0.12 * box_sin(0.41, 1.0 + 0.7 * k, x) * box_sin(0.29, 0.4, y) + 0.08 * box_sin(0.23, 2.0 - k, x);
    return v;
}

// Zero-mean noise, uniform in [-1, 1), a hash of the pixel, the frame and the component.
double noise(int i, int j, int t, int k) {
    uint64_t z = (uint64_t)i * 0x9E3779B97F4A7C15ull ^ (uint64_t)j * 0xC2B2AE3D27D4EB4Full ^ (uint64_t)(4 * t + k + 1) * 0x165667B19E3779F9ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1p-52 - 1.0;
}

// A camera panned with the plane: identity but for the NDC translation.
void pan(int t, double m[16]) {
    for (int i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0 : 0.0;
    m[12] = 2.0 * kVx * t / kW;
    m[13] = 2.0 * kVy * t / kH;
}

// One frame's inputs: samples per channel (texture + amplitude * noise; the
// 4-component channels' alpha a constant 1), depth 0.5, the pan's matrices.
struct Frame {
    std::vector<float> depth = std::vector<float>((size_t)kW * kH, 0.5f);
    std::vector<std::vector<float>> samples, base;
    std::vector<rrc_channel_input> inputs;
    rrc_frame_desc desc = frame_desc();

    Frame(const std::vector<rrc_channel_desc>& chs, int t, double amplitude) {
        for (const rrc_channel_desc& c : chs) {
            const int m = (int)c.components;
            std::vector<float> s((size_t)kW * kH * m), b(s.size());
            for (int j = 0; j < kH; ++j)
                for (int i = 0; i < kW; ++i)
                    for (int k = 0; k < m; ++k) {
                        const size_t e = ((size_t)j * kW + i) * m + k;
                        s[e] = k == 3 ? 1.0f : (float)(texel(i, j, t, k) + amplitude * noise(i, j, t, k));
                        b[e] = k == 3 ? 1.0f : (float)texel(i, j, t, k, false);
                    }
            samples.push_back(std::move(s));
            base.push_back(std::move(b));
        }
        for (size_t c = 0; c < chs.size(); ++c) {
            inputs.push_back(channel_input(samples[c].data()));
            if (chs[c].residual) inputs.back().fallback = base[c].data();
        }
        desc.frame_index = (uint64_t)t;
        desc.depth = depth.data();
        desc.channel_count = (uint32_t)inputs.size();
        desc.channels = inputs.data();
        pan(t, desc.view_proj);
        pan(t - 1, desc.prev_view_proj);
    }
    Frame(const Frame&) = delete;
};

rrc_context_desc plane_context(const std::vector<rrc_channel_desc>& chs) {
    rrc_context_desc d = context_desc(kW, kH, chs);
    d.reprojection = RRC_REPROJECTION_CAMERA;
    // UNORM16's epsilon (one step) is far above the CAMERA transform's fp32
    // error on the plane: no hit decision near its threshold.  (FLOAT32's
    // 4 ulp lies within it: every hit would be flagged and skipped.)
    d.depth_format = RRC_DEPTH_FORMAT_UNORM16;
    return d;
}

rrc_channel_desc gated(rrc_channel_desc d, float kappa) {
    d.gate_kappa = kappa;
    return d;
}

struct Stats {
    int64_t compared = 0, skipped = 0, hits = 0, capped = 0, uncertain = 0, other_uncertain = 0, caught_off = 0;
    int64_t uncertain_differ = 0;  // uncertain pixels where the kernel did take another age
    int64_t caught_kappa = 0;      // ages the reference at 1.25 kappa gets wrong
};

// The tolerance of tests/support/tolerance.h plus rectification's fp32 box.
double value_tolerance(const rrc_ref::FrameResult& r, const rrc_ref::PreviousFrame& prev, size_t ch, uint32_t m, size_t i, uint32_t q,
                       bool fp16, const float* prev_jitter) {
    const rrc_ref::ChannelResult& rc = r.channels[ch];
    const double spread =
        prev.valid ? history_spread(prev.channels[ch].history, m, q, kW, kH, r.uv_prev_x[i], r.uv_prev_y[i], prev_jitter) : 0.0;
    return arithmetic_tolerance(rc.out[m * i + q], rc.exact[m * i + q], fp16) + position_tolerance(spread, kW, kH) + rc.rectify_err[m * i + q];
}

// Runs the channels over the pan, comparing each frame with the reference
// from the kernel's history and ages and the reference's own gate state.
Stats run_against_reference(const char* name, const std::vector<rrc_channel_desc>& chs, double amplitude) {
    Stats st;
    Context ctx(plane_context(chs));
    if (!ctx) {
        ADD_FAILURE() << name << ": context refused: " << rrc_last_error();
        return st;
    }
    std::vector<rrc_channel_desc> off_chs = chs;  // the wrong variant: no gate
    for (rrc_channel_desc& d : off_chs) d.gate_kappa = 0.0f;
    rrc_context_desc off = ctx.desc();
    off.channels = off_chs.data();
    std::vector<rrc_channel_desc> wide_chs = chs;  // the wrong variant: a quarter larger kappa
    for (rrc_channel_desc& d : wide_chs) d.gate_kappa *= 1.25f;
    rrc_context_desc wide = ctx.desc();
    wide.channels = wide_chs.data();

    Mismatches masks(std::string(name) + " mask"), ages(std::string(name) + " age"), values(std::string(name) + " value");
    rrc_ref::PreviousFrame prev;
    const size_t n = (size_t)kW * kH;
    for (int t = 0; t < kFrames; ++t) {
        Frame f(chs, t, amplitude);
        const FrameResult k = ctx.run(f.desc);
        const rrc_ref::FrameResult r = rrc_ref::run_frame(ctx.desc(), prev, f.desc);
        const rrc_ref::FrameResult r_off = rrc_ref::run_frame(off, prev, f.desc), r_wide = rrc_ref::run_frame(wide, prev, f.desc);
        for (size_t i = 0; i < n; ++i) {
            if (r.near_threshold[i] || r.near_nearest_edge[i]) {
                ++st.skipped;
                continue;
            }
            if (k.mask[i] != r.mask[i]) {
                masks.add() << "frame " << t << " pixel (" << i % kW << "," << i / kW << ") kernel " << int(k.mask[i]) << " reference "
                            << int(r.mask[i]);
                continue;
            }
            ++st.compared;
            st.hits += (r.mask[i] & RRC_MASK_HIT) != 0;
            for (size_t ch = 0; ch < chs.size(); ++ch) {
                const uint32_t m = chs[ch].components;
                const bool fp16 = chs[ch].precision == RRC_HISTORY_FP16;
                const rrc_ref::ChannelResult& rc = r.channels[ch];
                st.capped += rc.gate_capped[i];
                // A cap within fp32 error of a step of its floor: any age of the
                // reference's range is right, and the value follows it (skipped).
                if (rc.gate_uncertain[i]) {
                    ++st.uncertain;
                    st.uncertain_differ += k.age[ch][i] != rc.age[i];
                    if (k.age[ch][i] < rc.gate_age_lo[i] || k.age[ch][i] > rc.gate_age_hi[i])
                        ages.add() << "frame " << t << " pixel (" << i % kW << "," << i / kW << ") channel " << ch << " kernel "
                                   << k.age[ch][i] << " outside the reference's range [" << rc.gate_age_lo[i] << ", " << rc.gate_age_hi[i]
                                   << "]";
                    continue;
                }
                if (rc.antilag_uncertain[i] || rc.blur_uncertain[i] || rc.view_uncertain[i]) {
                    ++st.other_uncertain;
                    continue;
                }
                st.caught_kappa += r_wide.channels[ch].age[i] != rc.age[i];
                if (k.age[ch][i] != rc.age[i])
                    ages.add() << "frame " << t << " pixel (" << i % kW << "," << i / kW << ") channel " << ch << " kernel " << k.age[ch][i]
                               << " reference " << rc.age[i] << " (N_g " << rc.gate_age[i] << ", beta " << rc.gate_beta[i] << " +- "
                               << rc.gate_beta_err[i] << ", varsigma " << rc.gate_sq[i] << " +- " << rc.gate_sq_err[i] << ", d "
                               << rc.gate_d[i] << ")";
                bool caught = false;
                for (uint32_t q = 0; q < m; ++q) {
                    const double kv = k.values[ch][m * i + q], rv = rc.out[m * i + q];
                    const double tol = value_tolerance(r, prev, ch, m, i, q, fp16, f.desc.prev_jitter);
                    if (!(std::fabs(kv - rv) <= tol))
                        values.add() << "frame " << t << " pixel (" << i % kW << "," << i / kW << ") channel " << ch << " component " << q
                                     << " kernel " << kv << " reference " << rv << " (age kernel " << k.age[ch][i] << " reference "
                                     << rc.age[i] << ")";
                    caught = caught || std::fabs(r_off.channels[ch].out[m * i + q] - rv) > 2 * tol;
                }
                st.caught_off += caught;
            }
        }
        prev = kernel_state(f.depth, k);
        rrc_ref::carry_gate_state(prev, r);  // the kernel's gate state is not read back: the reference's own
    }
    std::printf("%-12s compared %lld skipped %lld hits %lld; gate: capped %lld uncertain %lld (the kernel's age differs on %lld); "
                "other caps uncertain %lld;\n%-12s wrong variants would fail: the gate off on %lld values, 1.25 kappa on %lld ages\n",
                name, (long long)st.compared, (long long)st.skipped, (long long)st.hits, (long long)st.capped, (long long)st.uncertain,
                (long long)st.uncertain_differ, (long long)st.other_uncertain, "", (long long)st.caught_off, (long long)st.caught_kappa);
    EXPECT_GT(st.compared, (int64_t)n * kFrames * 9 / 10) << name << ": too few pixels compared";
    EXPECT_GT(st.hits, (int64_t)n * (kFrames - 1) * 9 / 10) << name << ": too few hits";
    EXPECT_GT(st.capped, 1000) << name << ": the gate hardly capped any history";
    EXPECT_LE(st.uncertain, st.capped / 20 + 5) << name << ": too many pixels with an uncertain gate age";
    EXPECT_GT(st.caught_off, 1000) << name << ": the comparison would not notice the gate off";
    EXPECT_GT(st.caught_kappa, 300) << name << ": the comparison would not notice another kappa";
    return st;
}

// The channels: every precision, filter and blend, the gate with the other
// blend-row options (rectification and the lag detector share H before the
// clamp; the blur bound's cap composes with N_g).
std::vector<rrc_channel_desc> gate_channels() {
    std::vector<rrc_channel_desc> c = {
        gated(channel("g1f", 1, 0.95f, RRC_HISTORY_FP32, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR), 1.25f),
        gated(channel("g4h", 4, 0.9f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_CATMULL_ROM), 2.0f),
        gated(channel("g1h", 1, 0.9f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_GAUSSIAN), 1.5f),
        gated(channel("g4f", 4, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_BILINEAR, 32), 2.5f),
    };
    c[1].rectify = 1;
    c[1].rectify_gamma = 1.5f;
    c[1].antilag = 1;
    c[1].antilag_threshold = 0.25f;
    c[2].blur_bound = 2.0f;
    return c;
}

TEST(GateKernel, CleanPanMatchesTheReference) { run_against_reference("gate clean", gate_channels(), 0.0); }

TEST(GateKernel, NoisyPanMatchesTheReference) { run_against_reference("gate noisy", gate_channels(), 0.1); }

TEST(GateKernel, TheResidualsDeviationIsGated) {
    // A residual channel and its twin without the residual fed fl(s - b): the
    // same masks and ages every frame (the gate's caps included), the values the
    // twin's plus b within one fp32 rounding.
    std::vector<rrc_channel_desc> res = {gated(channel("r1f", 1, 0.95f, RRC_HISTORY_FP32, RRC_BLEND_AGE_AWARE), 1.25f)};
    res[0].residual = 1;
    std::vector<rrc_channel_desc> twin = res;
    twin[0].residual = 0;
    Context a(plane_context(res)), b(plane_context(twin));
    ASSERT_TRUE(a && b);
    const size_t n = (size_t)kW * kH;
    int64_t age_diff = 0, mask_diff = 0, value_diff = 0, capped_apart = 0;
    for (int t = 0; t < kFrames; ++t) {
        Frame f(res, t, 0.05);
        std::vector<float> r(n);
        for (size_t e = 0; e < n; ++e) r[e] = f.samples[0][e] - f.base[0][e];  // fp32, as the kernel forms it
        rrc_channel_input in = channel_input(r.data());
        rrc_frame_desc td = f.desc;
        td.channels = &in;
        const FrameResult ka = a.run(f.desc), kb = b.run(td);
        for (size_t i = 0; i < n; ++i) {
            mask_diff += ka.mask[i] != kb.mask[i];
            age_diff += ka.age[0][i] != kb.age[0][i];
            capped_apart += ka.age[0][i] < (uint16_t)std::min(t + 1, 255);  // younger than the plain run's age: a cap acted
            const float want = kb.values[0][i] + f.base[0][i];
            value_diff += !(std::fabs(ka.values[0][i] - want) <= 2.0 * FLT_EPSILON * std::fabs(want) + FLT_MIN);
        }
    }
    std::printf("residual gate: capped %lld, mask %lld age %lld value %lld differences from the twin\n", (long long)capped_apart,
                (long long)mask_diff, (long long)age_diff, (long long)value_diff);
    EXPECT_EQ(mask_diff, 0);
    EXPECT_EQ(age_diff, 0) << "the residual channel's gate does not see the residual";
    EXPECT_EQ(value_diff, 0);
    EXPECT_GT(capped_apart, 1000) << "the gate hardly acted on the residual";
}

// ---- With a spatial fill ----------------------------------------------------------

// The twin of a fill channel: no fill, and a residual channel's history as a
// plain channel fed fl(s - b) (TheResidualsDeviationIsGated: the same history,
// ages and gate state), so that its values are the history the fill reads.
rrc_channel_desc fill_twin(rrc_channel_desc d) {
    d = without_fill(d);
    d.residual = 0;
    return d;
}

// Runs the fill channels and their twins over the pan; compares the displayed
// values with the reference's fill of the twin's history and ages and of the
// reference's own gate state, which it carries as run_against_reference does.
void run_fill_against_reference(const char* name, const std::vector<rrc_channel_desc>& chs, double amplitude) {
    std::vector<rrc_channel_desc> twin_chs;
    for (const rrc_channel_desc& d : chs) twin_chs.push_back(fill_twin(d));
    Context ctx(plane_context(chs)), twin(plane_context(twin_chs));
    ASSERT_TRUE(ctx && twin) << rrc_last_error();
    Mismatches masks(std::string(name) + " mask (fill vs twin)"), ages(std::string(name) + " age (fill vs twin)"),
        values(std::string(name) + " displayed value");
    const size_t n = (size_t)kW * kH;
    int64_t filled = 0, compared = 0, skipped = 0, weighed = 0, excluded = 0;
    double max_ratio = 0;
    std::vector<int64_t> excluded_by(chs.size(), 0);
    // The wrong variants: the fill without the gate's weighing; v_p = varsigma_p
    // (beta_p left out); a quarter larger kappa; the previous frame's state.
    const char* variant_names[] = {"without the gate's weighing", "beta ignored", "1.25 kappa", "the previous frame's state"};
    const size_t kVariants = 4;
    std::vector<std::vector<int64_t>> caught(kVariants, std::vector<int64_t>(chs.size(), 0));
    std::vector<rrc_channel_desc> wide_chs = chs;
    for (rrc_channel_desc& d : wide_chs) d.gate_kappa *= 1.25f;
    rrc_context_desc wide = ctx.desc();
    wide.channels = wide_chs.data();
    rrc_ref::PreviousFrame prev;
    for (int t = 0; t < kFrames; ++t) {
        Frame f(chs, t, amplitude);
        // A fill's fallback: the smooth base (with a residual it is the base already).
        for (size_t c = 0; c < chs.size(); ++c)
            if (chs[c].fill_prior > 0) f.inputs[c].fallback = f.base[c].data();
        // The twin's inputs: a residual channel's residual fl(s - b) as its samples.
        std::vector<std::vector<float>> residual(chs.size());
        std::vector<rrc_channel_input> twin_inputs;
        for (size_t c = 0; c < chs.size(); ++c) {
            if (chs[c].residual) {
                residual[c].resize(f.samples[c].size());
                for (size_t e = 0; e < residual[c].size(); ++e)
                    residual[c][e] = f.samples[c][e] - f.base[c][e];  // fp32, as the kernel forms it
            }
            twin_inputs.push_back(channel_input(chs[c].residual ? residual[c].data() : f.samples[c].data()));
        }
        rrc_frame_desc twin_desc = f.desc;
        twin_desc.channels = twin_inputs.data();
        const FrameResult k = ctx.run(f.desc), tw = twin.run(twin_desc);
        // The reference's gate state of this frame (the twin's: the fill does not touch it).
        const rrc_ref::FrameResult r = rrc_ref::run_frame(twin.desc(), prev, twin_desc);
        for (size_t c = 0; c < chs.size(); ++c) {
            const uint32_t m = chs[c].components;
            const std::vector<float> zero(chs[c].residual ? n * m : 0, 0.0f);  // a residual's prior: a residual of 0
            const rrc_ref::ChannelResult& rc = r.channels[c];
            rrc_ref::FillInputs fin{tw.values[c].data(), tw.age[c].data(), f.depth.data(),
                                    chs[c].residual ? zero.data() : f.inputs[c].fallback};
            fin.gate_beta = rc.gate_beta.data();
            fin.gate_sq = rc.gate_sq.data();
            fin.gate_beta_err = rc.gate_beta_err.data();
            fin.gate_sq_err = rc.gate_sq_err.data();
            const rrc_ref::FillResult ref = rrc_ref::spatial_fill(ctx.desc(), c, fin);
            rrc_ref::FillOptions no_gate;
            no_gate.gate = false;
            const rrc_ref::FillResult off = rrc_ref::spatial_fill(ctx.desc(), c, fin, no_gate);
            std::vector<rrc_ref::FillResult> variant(kVariants);
            variant[0] = off;
            const std::vector<double> zero_beta(n, 0.0);
            rrc_ref::FillInputs vin = fin;
            vin.gate_beta = zero_beta.data();
            variant[1] = rrc_ref::spatial_fill(ctx.desc(), c, vin);
            variant[2] = rrc_ref::spatial_fill(wide, c, fin);
            const std::vector<double> none(n, 0.0);
            vin = fin;
            vin.gate_beta = prev.valid && !prev.channels[c].gate_beta.empty() ? prev.channels[c].gate_beta.data() : none.data();
            vin.gate_sq = prev.valid && !prev.channels[c].gate_sq.empty() ? prev.channels[c].gate_sq.data() : none.data();
            vin.gate_beta_err = vin.gate_sq_err = nullptr;
            variant[3] = rrc_ref::spatial_fill(ctx.desc(), c, vin);
            for (size_t i = 0; i < n; ++i) {
                // The fill is display-only: the twin's ages (and mask).
                if (k.age[c][i] != tw.age[c][i])
                    ages.add() << "frame " << t << " pixel " << i << " channel " << c << " fill " << k.age[c][i] << " twin "
                               << tw.age[c][i];
                if (c == 0 && k.mask[i] != tw.mask[i]) masks.add() << "frame " << t << " pixel " << i;
                if (!ref.filled[i] && !chs[c].residual) continue;  // v_p: the twin's value (finishing_reference_test checks it)
                filled += ref.filled[i];
                if (ref.near_threshold[i]) {
                    ++skipped;
                    continue;
                }
                ++compared;
                weighed += ref.filled[i] && rc.gate_sq[i] > 0.0;
                excluded += ref.gate_excluded[i] > 0;
                excluded_by[c] += ref.gate_excluded[i] > 0;
                bool differs[kVariants] = {false, false, false, false};
                for (uint32_t q = 0; q < m; ++q) {
                    const size_t e = m * i + q;
                    // A residual's displayed value: the fill plus this frame's base, one more fp32 rounding.
                    const double b = chs[c].residual ? f.base[c][e] : 0.0;
                    const double rv = ref.shown[e] + b, kv = k.values[c][e];
                    const double tol = arithmetic_tolerance(rv, ref.exact[e] + b, false) + ref.err[e] +
                                       (chs[c].residual ? 2.0 * FLT_EPSILON * std::fabs(rv) : 0.0);
                    if (!(std::fabs(kv - rv) <= tol))
                        values.add() << "frame " << t << " pixel (" << i % kW << "," << i / kW << ") channel " << c << " component " << q
                                     << " kernel " << kv << " reference " << rv << " (without the gate's weighing " << off.shown[e] + b
                                     << ") history " << tw.values[c][e] << " age " << tw.age[c][i] << " neighbours "
                                     << int(ref.neighbours[i]) << " left out " << int(ref.gate_excluded[i]) << " beta " << rc.gate_beta[i]
                                     << " varsigma " << rc.gate_sq[i];
                    max_ratio = std::max(max_ratio, std::fabs(kv - rv) / tol);
                    for (size_t v = 0; v < kVariants; ++v)
                        differs[v] = differs[v] || std::fabs(variant[v].shown[e] - ref.shown[e]) > 2 * tol;
                }
                for (size_t v = 0; v < kVariants; ++v) caught[v][c] += differs[v];
            }
        }
        prev = rrc_test::kernel_state(f.depth, tw);
        rrc_ref::carry_gate_state(prev, r);  // the kernel's gate state is not read back: the reference's own
    }
    std::printf(
        "%-12s filled %lld compared %lld skipped (a test near its threshold) %lld weighed (varsigma > 0) %lld with neighbours "
        "left out %lld (per channel",
        name, (long long)filled, (long long)compared, (long long)skipped, (long long)weighed, (long long)excluded);
    for (int64_t e : excluded_by) std::printf(" %lld", (long long)e);
    std::printf("); max error %.3g of the tolerance\n", max_ratio);
    EXPECT_GT(weighed, 1000) << name << ": too few filled pixels with a noise estimate";
    for (size_t c = 0; c < chs.size(); ++c)
        EXPECT_GT(excluded_by[c], 50) << name << " channel " << c << ": the gate hardly left a neighbour out";
    for (size_t v = 0; v < kVariants; ++v) {
        std::printf("  wrong variant %-28s would fail on pixels (per channel)", variant_names[v]);
        for (size_t c = 0; c < chs.size(); ++c) std::printf(" %lld", (long long)caught[v][c]);
        std::printf("\n");
        for (size_t c = 0; c < chs.size(); ++c)
            EXPECT_GT(caught[v][c], 200) << name << " channel " << c << ": the comparison would not notice " << variant_names[v];
    }
    EXPECT_LT(skipped, compared / 20) << name << ": too many pixels with a test near its threshold";
}

// Gated channels with a fill: 1 and 4 components, fp16 (the packed 1-component
// history too) and fp32, a fallback, and a residual (its stored residuals
// weighed, its prior a residual of 0, the base added after).
std::vector<rrc_channel_desc> gate_fill_channels() {
    std::vector<rrc_channel_desc> c = {
        filled(gated(channel("f1f", 1, 0.95f, RRC_HISTORY_FP32, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR), 1.25f), 4, 1, 0.0f),
        filled(gated(channel("f4h", 4, 0.9f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_CATMULL_ROM), 2.0f), 4, 2, 2.0f),
        filled(gated(channel("f1h", 1, 0.9f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_GAUSSIAN), 1.5f), 8, 1, 0.0f),
        filled(gated(channel("r1f", 1, 0.95f, RRC_HISTORY_FP32, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR), 1.25f), 4, 2, 1.0f),
    };
    c[3].residual = 1;
    return c;
}

TEST(GateKernel, CleanPanFillWeighsByTheGate) { run_fill_against_reference("fill clean", gate_fill_channels(), 0.0); }

TEST(GateKernel, NoisyPanFillWeighsByTheGate) { run_fill_against_reference("fill noisy", gate_fill_channels(), 0.1); }

// ---- Validation ----------------------------------------------------------------

// Creates a context of a plain channel and `c` (channel 1); returns the result
// and the last error; nothing may be created on failure.
rrc_result create(const rrc_channel_desc& c, std::string* message) {
    std::vector<rrc_channel_desc> chs = {channel("plain", 1, 0.5f), c};
    rrc_context_desc d = plane_context(chs);
    rrc_context* ctx = nullptr;
    const rrc_result r = rrc_context_create(&d, &ctx);
    *message = r == RRC_SUCCESS ? "" : rrc_last_error();
    if (r != RRC_SUCCESS) EXPECT_EQ(ctx, nullptr) << "a refused description created a context";
    rrc_context_destroy(ctx);
    return r;
}

TEST(GateValidation, TheSectionsRefusalsNameTheMember) {
    std::string message;
    const rrc_channel_desc base = channel("g", 1, 0.5f, RRC_HISTORY_FP32, RRC_BLEND_AGE_AWARE);
    // In range: (0, 16].
    for (float kappa : {1e-3f, 2.0f, RRC_MAX_GATE_KAPPA}) EXPECT_EQ(create(gated(base, kappa), &message), RRC_SUCCESS) << kappa << ": " << message;
    // Out of range, infinite, NaN (the option table's test covers -1, 1e30 and NaN through the library's resolver).
    for (float kappa : {std::nextafter(RRC_MAX_GATE_KAPPA, INFINITY), -1e-3f, INFINITY, -INFINITY, std::numeric_limits<float>::quiet_NaN()}) {
        EXPECT_EQ(create(gated(base, kappa), &message), RRC_ERROR_INVALID_ARGUMENT) << kappa;
        EXPECT_NE(message.find("channels[1].gate_kappa"), std::string::npos) << kappa << ": " << message;
    }
    // With a confidence: the gate's state takes the weight's place.
    rrc_channel_desc conf = gated(base, 2.0f);
    conf.confidence = 1;
    EXPECT_EQ(create(conf, &message), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(message.find("channels[1].gate_kappa"), std::string::npos) << message;
    conf.gate_kappa = 0.0f;  // off: a confidence is fine
    EXPECT_EQ(create(conf, &message), RRC_SUCCESS) << message;
    // REUSE: a shading cache never blends.
    rrc_channel_desc reuse = gated(channel("g", 1, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_REUSE), 2.0f);
    EXPECT_EQ(create(reuse, &message), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(message.find("channels[1]"), std::string::npos) << message;
    EXPECT_NE(message.find("REUSE"), std::string::npos) << message;
    EXPECT_NE(message.find("gate_kappa"), std::string::npos) << message;
}

}  // namespace
