// Extreme magnitudes (docs/measurements/STABILITY.md, "Fast cases", rows "magnitudes"): every pixel of an 8x16 static image holds one
// magnitude class, from denormals through 1e-30 .. 1e30 to FLT_MAX, both
// signs, the fp16 overflow range (> 65504) and pixels that swing between
// ±1e30 or between 1e-30 and 1e30 from frame to frame.  Samples vary by
// up to 50% around the class (same sign), 40 frames.
//
// A: no jitter (each pixel reprojects onto itself): every channel against
//    the double-precision reference, taking the kernel's previous state, to
//    a purely relative tolerance (1e-5 of the largest of |r|, |H| and |s|: a
//    blend of ±1e30 cancels; plus one fp16 step for fp16, plus FLT_MIN where a
//    driver may flush denormals).  fp16 values beyond 65504
//    must be exactly ±65504.
// B: a sub-pixel jitter that changes every frame, so bilinear and Catmull-Rom
//    mix neighbours of wildly different magnitude with weights that are not
//    exact in fp32: every value must be finite and inside the range of what
//    it was made from (the 4x4 previous texels and s).  Texels at exactly
//    ±FLT_MAX are where fp32 weights summing to 1 + ulp would round to ±Inf.
#include "reference/rrc_reference.h"
#include "stability_report.h"
#include "stability_util.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

using namespace rrc_stab;
using rrc_test::channel;

namespace {

constexpr int kW = 8, kH = 16, kFrames = 40;  // powers of two: pixel centres reproject exactly

// The sample of pixel p at frame t.  Rows 0-5: one magnitude class a pixel,
// both signs; rows 6-9: values that swing; rows 10-15: blocks of exactly
// +FLT_MAX and -FLT_MAX, where fp32 bilinear weights that sum to 1 + ulp
// would round the resampled history to ±Inf.
float sample_of(size_t p, int t) {
    static const float mags[] = {0.0f,    1.4e-45f, 1e-40f,   FLT_MIN,  1e-30f,   1e-20f, 1e-10f, 6e-8f, 6.1e-5f, 1e-3f, 0.5f,   1.0f,
                                 1000.0f, 2048.5f,  65504.0f, 65519.0f, 65520.0f, 1e5f,   1e10f,  1e20f, 1e30f,   1e38f, FLT_MAX};
    constexpr size_t kMags = sizeof mags / sizeof mags[0];
    const double u = noise01(9, t, p);
    const size_t row = p / kW, col = p % kW;
    if (p < 2 * kMags) {
        const float v = mags[p % kMags] * (p < kMags ? 1.0f : -1.0f);
        return (float)(v * (1.0 - 0.5 * u));  // never beyond |v|: FLT_MAX stays finite
    }
    if (row >= 10) return col < kW / 2 ? FLT_MAX : -FLT_MAX;
    switch (p % 4) {
        case 0: return (t % 2 ? 1e30f : -1e30f) * (float)(1.0 - 0.5 * u);              // sign swings
        case 1: return t % 2 ? 1e-30f : 1e30f;                                         // 60 decades a frame
        case 2: return (float)((t % 3 == 0 ? FLT_MAX : -FLT_MAX) * (1.0 - 0.01 * u));  // extremes, both signs
        default: return (float)(1e-38 * u);                                            // around FLT_MIN
    }
}

std::vector<rrc_channel_desc> channels_with(rrc_history_filter filter) {
    return {
        channel("f32", 1, 0.6f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, filter),
        channel("f16", 1, 0.6f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, filter),
        channel("f32conf", 4, 0.9f, RRC_HISTORY_FP32, RRC_BLEND_AGE_AWARE, filter, 0, 1),
        channel("f16x4", 4, 0.8f, RRC_HISTORY_FP16, RRC_BLEND_RUNNING_MEAN, filter, 16),
    };
}

// Jitter of frame t for the resampling test: generic fractions (weights that
// are not exact in fp32), changing every frame as a TAA host's would.
float jitter_of(int t) { return t < 0 ? 0.0f : (float)(0.9 * noise01(3, t, 0) - 0.45); }

FrameData frame_at(int t, const std::vector<rrc_channel_desc>& channels, bool jitter) {
    FrameData f = static_frame(kW, kH, t);
    if (jitter) {
        f.jitter[0] = jitter_of(t);
        f.jitter[1] = jitter_of(t + 1000);
        f.prev_jitter[0] = jitter_of(t - 1);
        f.prev_jitter[1] = t == 0 ? 0.0f : jitter_of(t - 1 + 1000);
    }
    const size_t n = kW * kH;
    for (const auto& c : channels) {
        std::vector<float> s(n * c.components);
        for (size_t p = 0; p < n; ++p)
            for (uint32_t k = 0; k < c.components; ++k) s[p * c.components + k] = sample_of((p + 7 * k) % n, t);
        f.samples.push_back(s);
        std::vector<float> w;
        if (c.confidence) {  // confidences from 0 (keeps H) through denormals to 1
            static const float conf[] = {1.0f, 0.5f, 0.0f, 1e-40f, 1e-30f, 0.999f};
            for (size_t p = 0; p < n; ++p) w.push_back(conf[(p + t) % 6]);
        }
        f.confidence.push_back(w);
    }
    return f;
}

rrc_ref::PreviousFrame previous_of(const FrameData& f, const rrc_test::FrameResult& k) {
    rrc_ref::PreviousFrame prev;
    prev.valid = true;
    prev.depth = f.depth;
    for (size_t c = 0; c < k.values.size(); ++c) prev.channels.push_back({k.values[c], k.age[c], k.weight[c]});
    return prev;
}

rrc_frame_desc desc_of(const FrameData& f, std::vector<rrc_channel_input>& inputs) {
    rrc_frame_desc d = rrc_test::frame_desc();
    d.frame_index = f.index;
    d.depth = f.depth.data();
    std::memcpy(d.view_proj, f.view_proj, sizeof d.view_proj);
    std::memcpy(d.prev_view_proj, f.prev_view_proj, sizeof d.prev_view_proj);
    std::memcpy(d.jitter, f.jitter, sizeof d.jitter);
    std::memcpy(d.prev_jitter, f.prev_jitter, sizeof d.prev_jitter);
    inputs.clear();
    for (size_t c = 0; c < f.samples.size(); ++c)
        inputs.push_back(rrc_test::channel_input(f.samples[c].data(), f.confidence[c].empty() ? nullptr : f.confidence[c].data()));
    d.channel_count = (uint32_t)inputs.size();
    d.channels = inputs.data();
    return d;
}

double fp16_step(double v) {
    double a = std::fabs(v);
    return a < 0x1p-14 ? 0x1p-24 : std::ldexp(1.0, std::ilogb(a) - 10);
}

TEST(Magnitudes, MatchTheReferenceRelativelyWithoutJitter) {
    const std::vector<rrc_channel_desc> channels = channels_with(RRC_HISTORY_FILTER_BILINEAR);
    rrc_test::Context ctx(static_desc(kW, kH, channels));
    ASSERT_TRUE(ctx);
    rrc_ref::PreviousFrame prev;
    double worst = 0;  // max error / tolerance
    int64_t clamped16 = 0, finite_values = 0;
    for (int t = 0; t < kFrames; ++t) {
        FrameData f = frame_at(t, channels, false);
        std::vector<rrc_channel_input> inputs;
        rrc_frame_desc d = desc_of(f, inputs);
        rrc_test::FrameResult k = ctx.run(d);
        rrc_ref::FrameResult r = rrc_ref::run_frame(ctx.desc(), prev, d);
        ASSERT_EQ(k.mask, r.mask) << "frame " << t;
        for (size_t c = 0; c < channels.size(); ++c) {
            const bool fp16 = channels[c].precision == RRC_HISTORY_FP16;
            for (size_t i = 0; i < k.values[c].size(); ++i) {
                const double kv = k.values[c][i], rv = r.channels[c].out[i], exact = r.channels[c].exact[i];
                ASSERT_TRUE(std::isfinite(kv)) << "channel " << c << " value " << i << " frame " << t << " reference " << rv;
                ++finite_values;
                // fp32 rounds each term of the blend: the error scales with the
                // largest of H (each pixel's own previous value here) and s, not
                // with a result that cancels (±1e30 swings).
                const double h = prev.valid ? prev.channels[c].history[i] : 0.0;
                const double scale = std::max({std::fabs(rv), std::fabs(h), std::fabs((double)f.samples[c][i])});
                const double tol = 1e-5 * scale + FLT_MIN + (fp16 ? fp16_step(exact) : 0.0);
                EXPECT_LE(std::fabs(kv - rv), tol)
                    << "channel " << c << " value " << i << " frame " << t << " kernel " << kv << " reference " << rv;
                worst = std::max(worst, std::fabs(kv - rv) / tol);
                if (fp16 && std::fabs(exact) >= 65504.0) {
                    EXPECT_EQ(std::fabs(kv), 65504.0) << "fp16 overflow must clamp to ±65504, value " << i;
                    ++clamped16;
                }
            }
            EXPECT_EQ(k.age[c], r.channels[c].age) << "channel " << c << " frame " << t;
            if (channels[c].confidence)
                for (size_t i = 0; i < k.weight[c].size(); ++i)
                    EXPECT_LE(std::fabs(k.weight[c][i] - r.channels[c].weight[i]), 1e-6 * r.channels[c].weight[i] + FLT_MIN);
        }
        prev = previous_of(f, k);
    }
    EXPECT_GT(clamped16, 0);
    report("magnitudes (8x16, 1e-45 .. FLT_MAX, both signs, 40 frames)", "no jitter: kernel vs double reference",
           "finite; |k - r| <= 1e-5·max(|r|, |H|, |s|) + FLT_MIN (+1 fp16 step); fp16 beyond 65504 = ±65504",
           format("all %lld values finite, max error/tolerance %.3f, %lld fp16 values clamped to ±65504", (long long)finite_values, worst,
                  (long long)clamped16));
}

TEST(Magnitudes, StayInsideTheirInputsRangeUnderResampling) {
    for (rrc_history_filter filter : {RRC_HISTORY_FILTER_BILINEAR, RRC_HISTORY_FILTER_CATMULL_ROM}) {
        const std::vector<rrc_channel_desc> channels = channels_with(filter);
        rrc_test::Context ctx(static_desc(kW, kH, channels));
        ASSERT_TRUE(ctx);
        std::vector<std::vector<float>> prev(channels.size());
        int64_t checked = 0;
        for (int t = 0; t < kFrames; ++t) {
            FrameData f = frame_at(t, channels, true);
            std::vector<rrc_channel_input> inputs;
            rrc_test::FrameResult k = ctx.run(desc_of(f, inputs));
            for (size_t c = 0; c < channels.size(); ++c) {
                const uint32_t m = channels[c].components;
                const bool fp16 = channels[c].precision == RRC_HISTORY_FP16;
                for (int j = 0; j < kH; ++j)
                    for (int i = 0; i < kW; ++i)
                        for (uint32_t q = 0; q < m; ++q) {
                            const size_t at = ((size_t)j * kW + i) * m + q;
                            const double v = k.values[c][at];
                            ASSERT_TRUE(std::isfinite(v)) << "filter " << filter << " channel " << c << " frame " << t;
                            double lo = f.samples[c][at], hi = lo;
                            if (t > 0)  // the 4x4 texels any of the filters can read (|jitter| < 0.5: around (i, j))
                                for (int y = j - 2; y <= j + 2; ++y)
                                    for (int x = i - 2; x <= i + 2; ++x) {
                                        const int cx = std::clamp(x, 0, kW - 1), cy = std::clamp(y, 0, kH - 1);
                                        const double h = prev[c][((size_t)cy * kW + cx) * m + q];
                                        lo = std::min(lo, h);
                                        hi = std::max(hi, h);
                                    }
                            if (fp16) {  // the store clamps and rounds
                                lo = std::clamp(lo, -65504.0, 65504.0);
                                hi = std::clamp(hi, -65504.0, 65504.0);
                                lo -= fp16_step(lo);
                                hi += fp16_step(hi);
                            }
                            const double slack = 1e-6 * std::max(std::fabs(lo), std::fabs(hi)) + FLT_MIN;
                            EXPECT_GE(v, lo - slack) << "filter " << filter << " channel " << c << " (" << i << "," << j << ") frame " << t;
                            EXPECT_LE(v, hi + slack) << "filter " << filter << " channel " << c << " (" << i << "," << j << ") frame " << t;
                            ++checked;
                        }
                prev[c] = k.values[c];
            }
        }
        report("magnitudes (8x16, 1e-45 .. FLT_MAX, both signs, 40 frames)",
               filter == RRC_HISTORY_FILTER_BILINEAR ? "changing jitter, bilinear" : "changing jitter, Catmull-Rom",
               "finite and inside [min, max] of the 4x4 previous texels and s", format("%lld values, all inside", (long long)checked));
    }
}

}  // namespace
