// Stiff λ over 10,000 frames of a stationary noisy signal (docs/measurements/STABILITY.md,
// "Reading the tables": λ sweep).  Every component of every pixel of a 32x32 static image of
// 4-component channels (4096 independent signals) gets s = 0.5 + U(-0.2, 0.2)
// each frame; FIXED blend, NEAREST history (each pixel keeps its own history:
// no resampling lowers the variance), λ in {0, 1e-6, 0.5, 0.9, 0.99, 0.999,
// 0.9999}, fp16 and fp32 history requested, all on the same samples.
//
// Per channel, over the second half of the run (every 5th frame):
//   bias      spatial mean of H against the true mean 0.5, relative;
//   variance  spatial variance of H against the exact law of the filter
//             started from its first sample, σ²[λ^2(t-1) + (1-λ)/(1+λ)(1 - λ^2(t-1))]
//             ((1-λ)/(1+λ)·σ² once λ^2t has died out);
//   numeric   the kernel against the same filter run in double on the same
//             samples: what the storage and the fp32 arithmetic add.
// And a CPU model of an fp16 history that is NOT promoted (fp32 blend, then
// round to nearest fp16, as the kernel stores it): it stalls once
// (1-λ)|s-H| < ulp(H)/2, so at λ = 0.999 its bias is ~3.6e-2.  The library
// therefore keeps fp16 history only up to λ_max = RRC_FP16_MAX_LAMBDA
// (docs/CONVENTIONS.md "The recursive filter (per channel)"); the kernel rows show the result.
#include "reference/rrc_reference.h"
#include "stability_report.h"
#include "stability_util.h"

#include <cmath>
#include <cstring>

using namespace rrc_stab;
using rrc_test::channel;

namespace {

constexpr int kW = 32, kH = 32, kC = 4, kFrames = 10000, kEvery = 5;
// Batches of 100 frames: synchronization validation costs grow with the square
// of a command buffer's length.
constexpr int kChunk = 100;
constexpr double kMean = 0.5, kAmp = 0.2, kSigma2 = kAmp * kAmp / 3.0;  // uniform ±a: a²/3
const char* const kArea = "λ sweep (10,000 frames, 32x32x4 signals, s = 0.5 + U(±0.2))";
// The λ values of docs/measurements/STABILITY.md's λ sweep, plus RRC_FP16_MAX_LAMBDA itself: the largest λ
// whose fp16 history is kept.
const double kLambdas[] = {0.0, 1e-6, 0.5, 0.9, RRC_FP16_MAX_LAMBDA, 0.99, 0.999, 0.9999};

struct Channel {
    float lambda;
    bool fp16;
    std::vector<double> exact;   // double filter, per pixel
    std::vector<float> model16;  // unpromoted fp16 model, per pixel (fp16 channels)
    double sum = 0, sum_exact = 0, sum_model16 = 0, sum_dev = 0, max_dev = 0;
    double var_ratio_sum = 0;
    int64_t samples = 0;
    uint64_t bits_hash = 1469598103934665603ull;  // FNV-1a over every value read back
};

// Clamp to ±65504 and round to the nearest fp16 (ties to even), on the float
// bits as the shader does; exact, and fast enough for 10^8 calls (the
// reference's rrc_ref::fp16_round is the slow, obviously-right version that
// the kernel tests use).
float round_fp16(float x) {
    x = std::min(std::max(x, -65504.0f), 65504.0f);
    if (std::fabs(x) < 6.103515625e-05f) return std::nearbyint(x * 16777216.0f) / 16777216.0f;  // subnormal grid 2^-24
    uint32_t b;
    std::memcpy(&b, &x, 4);
    b = (b + 0xFFFu + ((b >> 13) & 1u)) & ~0x1FFFu;
    std::memcpy(&x, &b, 4);
    return x;
}

// The kernel's blend in fp32, stored as the nearest fp16 (no promotion).
float model_fp16_step(float lambda, float h, float s) { return round_fp16(lambda * h + (1.0f - lambda) * s); }

double expected_variance(double lambda, int t) {  // t: 1-based frame count since the first sample
    double l2 = std::pow(lambda, 2.0 * (t - 1));
    return kSigma2 * (l2 + (1.0 - lambda) / (1.0 + lambda) * (1.0 - l2));
}

// The fast model agrees with the reference's rounding (on normals,
// subnormals, ties and the clamp).
TEST(LambdaSweep, Fp16ModelMatchesReferenceRounding) {
    for (int i = 0; i < 200000; ++i) {
        float x = (float)((2.0 * noise01(7, 0, i) - 1.0) * std::ldexp(1.0, (i % 48) - 30));
        if (i % 1000 == 0) x = 65519.0f + (float)(i % 7);
        ASSERT_EQ(round_fp16(x), (float)rrc_ref::fp16_round(x)) << x;
    }
}

TEST(LambdaSweep, BiasAndVarianceOver10000Frames) {
    std::vector<Channel> all;
    for (double l : kLambdas)
        for (bool fp16 : {true, false}) all.push_back({(float)l, fp16});
    const size_t n = (size_t)kW * kH * kC;  // signals per channel
    for (auto& c : all) {
        c.exact.assign(n, 0.0);
        c.model16.assign(n, 0.0f);
    }

    // Contexts of up to RRC_MAX_CHANNELS channels, all fed the same samples.
    for (size_t first = 0; first < all.size(); first += RRC_MAX_CHANNELS) {
        const size_t count = std::min<size_t>(RRC_MAX_CHANNELS, all.size() - first);
        std::vector<rrc_channel_desc> descs;
        for (size_t k = 0; k < count; ++k) {
            const Channel& c = all[first + k];
            std::string name = "c" + std::to_string(first + k);
            descs.push_back(channel(name.c_str(), kC, c.lambda, c.fp16 ? RRC_HISTORY_FP16 : RRC_HISTORY_FP32, RRC_BLEND_FIXED,
                                    RRC_HISTORY_FILTER_NEAREST));
        }
        rrc_test::Context ctx(static_desc(kW, kH, descs));
        ASSERT_TRUE(ctx);
        for (int t0 = 0; t0 < kFrames; t0 += kChunk) {
            std::vector<FrameData> frames;
            for (int t = t0; t < t0 + kChunk; ++t) {
                FrameData f = static_frame(kW, kH, (uint64_t)t);
                std::vector<float> s(n);
                for (size_t p = 0; p < n; ++p) s[p] = (float)(kMean + kAmp * (2.0 * noise01(42, t, p) - 1.0));
                f.samples.assign(count, s);
                f.read_values = t >= kFrames / 2 && t % kEvery == 0;
                frames.push_back(std::move(f));
            }
            std::vector<rrc_test::FrameResult> res = run_batch(ctx.get(), ctx.desc(), frames);
            for (int k = 0; k < kChunk; ++k) {
                const int t = t0 + k;
                ASSERT_EQ(res[k].stats.hits, t == 0 ? 0u : (uint64_t)kW * kH) << "frame " << t;
                for (size_t ci = 0; ci < count; ++ci) {
                    Channel& c = all[first + ci];
                    const std::vector<float>& s = frames[k].samples[ci];
                    for (size_t p = 0; p < n; ++p) {
                        c.exact[p] = t == 0 ? s[p] : c.lambda * c.exact[p] + (1.0 - c.lambda) * s[p];
                        if (c.fp16 && c.lambda > RRC_FP16_MAX_LAMBDA)
                            c.model16[p] = t == 0 ? round_fp16(s[p]) : model_fp16_step(c.lambda, c.model16[p], s[p]);
                    }
                    if (!frames[k].read_values) continue;
                    const std::vector<float>& h = res[k].values[ci];
                    double sum = 0, sum2 = 0, se = 0, sm = 0, dev = 0;
                    for (size_t p = 0; p < n; ++p) {
                        sum += h[p];
                        sum2 += (double)h[p] * h[p];
                        se += c.exact[p];
                        sm += c.model16[p];
                        dev += h[p] - c.exact[p];
                        c.max_dev = std::max(c.max_dev, std::fabs(h[p] - c.exact[p]));
                        uint32_t bits;
                        std::memcpy(&bits, &h[p], 4);
                        c.bits_hash = (c.bits_hash ^ bits) * 1099511628211ull;
                        ASSERT_TRUE(std::isfinite(h[p]));
                    }
                    double mean = sum / n;
                    double var = (sum2 - n * mean * mean) / (n - 1);
                    c.sum += mean;
                    c.sum_exact += se / n;
                    c.sum_model16 += sm / n;
                    c.sum_dev += dev / n;
                    c.var_ratio_sum += var / expected_variance(c.lambda, t + 1);
                    ++c.samples;
                }
            }
        }
    }

    for (const Channel& c : all) {
        // Above the limit an fp16 request is stored in fp32: bit for bit the
        // fp32 channel of the same λ (the next one in `all`).
        if (c.fp16 && c.lambda > RRC_FP16_MAX_LAMBDA)
            EXPECT_EQ(c.bits_hash, (&c)[1].bits_hash) << "λ=" << c.lambda << ": an fp16 request above RRC_FP16_MAX_LAMBDA is fp32";
        if (c.fp16 && c.lambda <= RRC_FP16_MAX_LAMBDA)
            EXPECT_NE(c.bits_hash, (&c)[1].bits_hash) << "λ=" << c.lambda << ": fp16 history kept";
        const double bias = c.sum / c.samples / kMean - 1.0;
        const double bias_exact = c.sum_exact / c.samples / kMean - 1.0;
        const double numeric = c.sum_dev / c.samples / kMean;
        const double var_ratio = c.var_ratio_sum / c.samples;
        const double law = (1.0 - c.lambda) / (1.0 + c.lambda);
        std::string name = format("λ=%g, fp16 asked%s", (double)c.lambda, c.lambda > RRC_FP16_MAX_LAMBDA ? " (stored fp32)" : "");
        if (!c.fp16) name = format("λ=%g, fp32", (double)c.lambda);
        report(kArea, name,
               c.lambda <= 0.999f ? "|bias| < 1e-3; var/law in [0.9, 1.1]; |numeric| < 1e-4" : "var/law in [0.9, 1.1]; |numeric| < 1e-4",
               format("bias %+.2e (the double filter on the same samples: %+.2e); var/law %.3f, law (1-λ)/(1+λ) = %.3g; "
                      "numeric %+.1e (max %.1e)",
                      bias, bias_exact, var_ratio, law, numeric, c.max_dev));
        // The bias bound (docs/measurements/STABILITY.md, "Reading the tables"); at λ = 0.9999 the first sample still
        // weighs e^-2 after 10,000 frames, so only the numeric part is bounded.
        if (c.lambda <= 0.999f) EXPECT_LT(std::fabs(bias), 1e-3) << name;
        EXPECT_LT(std::fabs(numeric), 1e-4) << name;
        EXPECT_GT(var_ratio, 0.9) << name;
        EXPECT_LT(var_ratio, 1.1) << name;
        if (c.fp16 && c.lambda > RRC_FP16_MAX_LAMBDA) {  // what fp16 storage would have done
            const double bias16 = c.sum_model16 / c.samples / kMean - 1.0;
            report(kArea, format("λ=%g, fp16 NOT promoted (CPU model of the kernel's store)", (double)c.lambda),
                   c.lambda == 0.999f ? "|bias| > 1e-3 (the stall the promotion removes)" : "reported", format("bias %+.2e", bias16));
            if (c.lambda == 0.999f) EXPECT_GT(std::fabs(bias16), 1e-3) << "the unpromoted fp16 model should stall at λ = 0.999";
        }
    }
}

}  // namespace
