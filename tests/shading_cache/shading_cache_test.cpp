// The shading cache (docs/CONVENTIONS.md, "The shading cache"), what
// tests/shading_cache/cache_reference_test.cpp leaves open:
//   - the REUSE variants it does not run (1 component fp16 bilinear, 4
//     components fp32 nearest) next to an accumulating channel, against the
//     independent reference fed the kernel's previous outputs;
//   - classify + resolve is BIT-IDENTICAL to rrc_frame_run on a twin context
//     given the same samples at the listed quads and NaN at every unlisted
//     REUSE pixel: mask, values, ages, stats, refreshed;
//   - classify's quad array: no quad twice, nothing written past quad_count,
//     the set is the quads of the mask without HIT; classify's counts;
//   - on a static scene, frame indices from just under 2^40 (stride 1 and 3):
//     every pixel refreshed exactly once every n frames, RANDOM refreshing
//     floor(Q/n) or ceil(Q/n) whole quads a frame, and the frame output's
//     refreshed / stats adding up to W * H;
//   - with no policy, the maximum lifetime alone: under a camera pan a pixel
//     whose source hit L frames in a row (age L) is REFRESHED, no age exceeds L.
// Every context runs under the validation layer (support/rrc_test_context.h).
#include "reference/cache.h"
#include "reference/params.h"
#include "reference/rrc_reference.h"
#include "support/cache_policy.h"
#include "support/flat_plane.h"
#include "support/kernel_state.h"
#include "support/rrc_test_context.h"
#include "support/scene_frames.h"
#include "support/split_frame.h"
#include "support/static_clip.h"
#include "support/tolerance.h"

#include <cmath>
#include <cstring>
#include <set>

using namespace rrc_test;

namespace {

// Output arrays start as values no call writes, so what a call left alone shows.
const OutputFill kUnwritten{0xAA, -1.0f, 0xBEEF};

// rrc_frame_run with every output read back, refreshed included.
struct FusedRun {
    FrameResult r;
    uint64_t refreshed = 0;
};

FusedRun run_fused(Context& ctx, const std::vector<rrc_channel_desc>& channels, const rrc_frame_desc& f) {
    FusedRun out;
    BoundOutput o(out.r, channels, (size_t)ctx.desc().width * ctx.desc().height, kUnwritten);
    EXPECT_EQ(rrc_frame_run(ctx.get(), &f, &o.frame), RRC_SUCCESS) << rrc_last_error();
    out.r.stats = o.frame.stats;
    out.refreshed = o.frame.refreshed;
    return out;
}

uint64_t count_bit(const std::vector<uint8_t>& mask, uint8_t bit) {
    uint64_t c = 0;
    for (uint8_t m : mask) c += (m & bit) ? 1 : 0;
    return c;
}

// Stats add up as CONVENTIONS.md states: misses = not HIT, not REFRESHED, not BACKGROUND.
void expect_stats(const std::vector<uint8_t>& mask, const rrc_frame_stats& s, uint64_t refreshed, const char* what) {
    uint64_t hits = 0, bg = 0, ref = 0, miss = 0;
    for (uint8_t m : mask) {
        if (m & RRC_MASK_BACKGROUND)
            ++bg;
        else if (m & RRC_MASK_HIT)
            ++hits;
        else if (m & RRC_MASK_REFRESHED)
            ++ref;
        else
            ++miss;
        EXPECT_FALSE((m & RRC_MASK_HIT) && (m & RRC_MASK_REFRESHED)) << what << ": a refreshed pixel is not a hit";
    }
    EXPECT_EQ(s.hits, hits) << what;
    EXPECT_EQ(s.background, bg) << what;
    EXPECT_EQ(refreshed, ref) << what;
    EXPECT_EQ(s.misses, miss) << what;
    EXPECT_EQ(s.hits + s.misses + s.background + refreshed, (uint64_t)mask.size()) << what;
}

const Policy kPolicies[] = {
    {"tiled_8x1", RRC_REFRESH_TILED, 8, 0, 0, 0},
    {"tiled_2x4_lifetime_5", RRC_REFRESH_TILED, 8, 2, 4, 5},
    {"random_3_lifetime_2", RRC_REFRESH_RANDOM, 3, 0, 0, 2},
};

std::vector<rrc_channel_desc> variant_channels() {
    return {channel("reuse1_fp16_bilinear", 1, 0.0f, RRC_HISTORY_FP16, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_BILINEAR),
            channel("reuse4_fp32_nearest", 4, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_NEAREST),
            channel("accum4_fp16_age_aware", 4, 0.8f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR)};
}

// A context of REUSE channels only: classify writes the HITs' channels and
// resolve runs on the listed quads only (docs/design/frame-plan.md).
std::vector<rrc_channel_desc> reuse_only_channels(bool fill) {
    std::vector<rrc_channel_desc> c = variant_channels();
    c.pop_back();
    if (fill) c[0].fill_age = 4, c[1].fill_age = 3;  // the shading cache's holes filled from cached neighbours
    return c;
}

// `reference`: also check the fused frames against the reference (without a fill: the finishing tests check the fill's).
void split_vs_fused(const Policy& pol, std::vector<rrc_channel_desc> channels, bool reference);

class SplitVsFused : public ::testing::TestWithParam<Policy> {};

TEST_P(SplitVsFused, BitIdenticalAndMatchingTheReference) { split_vs_fused(GetParam(), variant_channels(), true); }

class SplitVsFusedReuseOnly : public ::testing::TestWithParam<Policy> {};

TEST_P(SplitVsFusedReuseOnly, BitIdenticalAndMatchingTheReference) { split_vs_fused(GetParam(), reuse_only_channels(false), true); }
TEST_P(SplitVsFusedReuseOnly, WithAFillBitIdentical) { split_vs_fused(GetParam(), reuse_only_channels(true), false); }

void split_vs_fused(const Policy& pol, std::vector<rrc_channel_desc> channels, bool check_reference) {
    const int W = 64, H = 48, frames = 8;
    const size_t n = (size_t)W * H;
    rrc_scene::SceneConfig sc = scene_config(W, H, RRC_DEPTH_MODE_REVERSED);
    sc.jitter = true;
    rrc_scene::Scene scene(sc);
    rrc_context_desc desc = scene_context_desc(scene.config(), RRC_REPROJECTION_PREV_CLIP, channels);
    apply(pol, desc);
    Context fused(desc), split(desc);
    ASSERT_TRUE(fused);
    ASSERT_TRUE(split);

    rrc_ref::PreviousFrame prev;
    int64_t compared = 0, refreshed = 0, reused = 0;
    for (int t = 0; t < frames; ++t) {
        SCOPED_TRACE(std::string(pol.name) + " frame " + std::to_string(t));
        SceneFrameInputs in;
        in.frame = scene.render(t);
        make_frame_inputs(in, RRC_REPROJECTION_PREV_CLIP, channels);
        in.desc.frame_index = (1ull << 40) - 4 + (uint64_t)t;  // crosses 2^40

        const FusedRun k = run_fused(fused, channels, in.desc);
        expect_stats(k.r.mask, k.r.stats, k.refreshed, "fused");

        // ---- classify
        std::vector<uint8_t> classified(n, 0xAA);
        // The C API's array holds the quads only (the GPU list's header is the interop test's).
        std::vector<uint32_t> list(RRC_QUAD_LIST_BYTES(W, H) / 4 - RRC_QUAD_LIST_FIRST_QUAD + 1, 0xDEADBEEFu);
        rrc_classify_output co = rrc_host::rrc_struct<rrc_classify_output>(RRC_STRUCT_TYPE_CLASSIFY_OUTPUT);
        co.mask = classified.data();
        co.quads = list.data();
        co.quad_capacity = (uint32_t)list.size() - 1;  // the last word is a guard
        const rrc_frame_desc geometry = geometry_of(in.desc);
        ASSERT_EQ(rrc_frame_classify(split.get(), &geometry, &co), RRC_SUCCESS) << rrc_last_error();
        for (size_t i = 0; i < n; ++i)
            ASSERT_EQ(classified[i], k.r.mask[i] & ~RRC_MASK_INVALID_SAMPLE) << "classify's mask is the fused one, pixel " << i;
        const uint32_t c = co.quad_count;
        ASSERT_LE(c, co.quad_capacity);
        for (size_t w = c; w < list.size(); ++w) ASSERT_EQ(list[w], 0xDEADBEEFu) << "classify wrote past quad_count, word " << w;
        const std::set<uint32_t> quads(list.begin(), list.begin() + c);
        EXPECT_EQ(quads.size(), c) << "a quad listed twice";
        EXPECT_EQ(quads, rrc_ref::listed_quads(k.r.mask, W, H));
        EXPECT_EQ(co.stats.hits, k.r.stats.hits);
        EXPECT_EQ(co.stats.misses, k.r.stats.misses);
        EXPECT_EQ(co.stats.background, k.r.stats.background);
        EXPECT_EQ(co.refreshed, k.refreshed);

        // ---- resolve: REUSE samples only at the listed quads, NaN elsewhere
        HostSamples host(channels, in.desc, quads, W, H);
        FrameResult sr;
        BoundOutput o(sr, channels, n, kUnwritten);
        ASSERT_EQ(rrc_frame_resolve(split.get(), &host.desc, &o.frame), RRC_SUCCESS) << rrc_last_error();
        EXPECT_EQ(rrc_frame_resolve(split.get(), &host.desc, &o.frame), RRC_ERROR_INVALID_ARGUMENT) << "one resolve a classification";
        EXPECT_EQ(sr.mask, k.r.mask) << "split mask == fused mask, bit for bit";
        for (size_t ch = 0; ch < channels.size(); ++ch) {
            EXPECT_EQ(sr.age[ch], k.r.age[ch]) << "ages, channel " << ch;
            ASSERT_EQ(sr.values[ch].size(), k.r.values[ch].size());
            EXPECT_EQ(std::memcmp(sr.values[ch].data(), k.r.values[ch].data(), sr.values[ch].size() * sizeof(float)), 0)
                << "values bit-identical, channel " << ch;
        }
        EXPECT_EQ(o.frame.stats.hits, k.r.stats.hits);
        EXPECT_EQ(o.frame.stats.misses, k.r.stats.misses);
        EXPECT_EQ(o.frame.stats.background, k.r.stats.background);
        EXPECT_EQ(o.frame.stats.invalid_samples, k.r.stats.invalid_samples);
        EXPECT_EQ(o.frame.refreshed, k.refreshed);

        // ---- the fused kernel against the reference
        const rrc_ref::FrameResult r = rrc_ref::run_frame(fused.desc(), prev, in.desc);
        for (size_t i = 0; i < n && check_reference; ++i) {
            if (r.near_threshold[i] || r.near_nearest_edge[i]) continue;
            ++compared;
            refreshed += (r.mask[i] & RRC_MASK_REFRESHED) ? 1 : 0;
            ASSERT_EQ(k.r.mask[i], r.mask[i]) << "pixel (" << i % W << "," << i / W << ")";
            for (size_t ch = 0; ch < channels.size(); ++ch) {
                ASSERT_EQ(k.r.age[ch][i], r.channels[ch].age[i]) << "pixel " << i << " channel " << ch;
                const uint32_t m = channels[ch].components;
                const bool fp16 = channels[ch].precision == RRC_HISTORY_FP16;
                for (uint32_t q = 0; q < m; ++q) {
                    const double kv = k.r.values[ch][m * i + q], rv = r.channels[ch].out[m * i + q];
                    const double spread = prev.valid ? history_spread(prev.channels[ch].history, m, q, W, H, r.uv_prev_x[i], r.uv_prev_y[i],
                                                                      in.desc.prev_jitter)
                                                     : 0.0;
                    const double tol = arithmetic_tolerance(rv, r.channels[ch].exact[m * i + q], fp16) + position_tolerance(spread, W, H);
                    EXPECT_LE(std::fabs(kv - rv), tol) << "pixel " << i << " channel " << ch << " component " << q;
                }
                if (channels[ch].blend == RRC_BLEND_REUSE && pol.lifetime) EXPECT_LE(k.r.age[ch][i], pol.lifetime);
            }
            if ((r.mask[i] & RRC_MASK_HIT) && r.channels[1].age[i] > 1) ++reused;
        }
        prev = kernel_state(in.frame.depth, k.r);
    }
    if (!check_reference) return;
    EXPECT_GT(refreshed, 0) << "the comparison must cover refreshes";
    EXPECT_GT(reused, 0) << "the comparison must cover reused values";
    EXPECT_GT(compared, (int64_t)n * frames * 8 / 10);
}

INSTANTIATE_TEST_SUITE_P(Policies, SplitVsFused, ::testing::ValuesIn(kPolicies),
                         [](const ::testing::TestParamInfo<Policy>& i) { return std::string(i.param.name); });
INSTANTIATE_TEST_SUITE_P(Policies, SplitVsFusedReuseOnly, ::testing::ValuesIn(kPolicies),
                         [](const ::testing::TestParamInfo<Policy>& i) { return std::string(i.param.name); });

// A classify that fails (quad_capacity too small) leaves the classification
// pending before it as it was: rrc.h, "on any error the context is left as
// it was".  The failing classify is a different frame (other geometry, some
// HITs resampled elsewhere, some misses), so that a classify that kept any
// of its work (mask, uploads, HITs' channels, list) would show in resolve.
TEST(ShadingCacheClassify, AFailedClassifyKeepsThePendingClassification) {
    const uint32_t W = 8, H = 4, n = W * H;
    std::vector<rrc_channel_desc> channels = {channel("shade", 4, 0.0f, RRC_HISTORY_FP16, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_BILINEAR)};
    rrc_context_desc d = context_desc(W, H, channels);
    d.reprojection = RRC_REPROJECTION_PREV_CLIP;
    Context fused(d), split(d);
    ASSERT_TRUE(fused);
    ASSERT_TRUE(split);
    std::vector<float> depth(n, 0.5f), clip = static_prev_clip(W, H, 0.5f), shade(4 * n);
    for (uint32_t i = 0; i < 4 * n; ++i) shade[i] = (float)((i * 37) % 101) / 101.0f;
    rrc_channel_input in = channel_input(shade.data());
    auto frame = [&](uint64_t index, const std::vector<float>& z, const std::vector<float>& c) {
        rrc_frame_desc f = frame_desc();
        f.frame_index = index;
        f.depth = z.data();
        f.reprojection = c.data();
        f.channel_count = 1;
        f.channels = &in;
        return f;
    };
    auto classify = [&](const rrc_frame_desc& f, uint32_t capacity, uint32_t* count) {
        std::vector<uint32_t> quads(RRC_QUAD_LIST_BYTES(W, H) / 4);
        rrc_classify_output co = rrc_host::rrc_struct<rrc_classify_output>(RRC_STRUCT_TYPE_CLASSIFY_OUTPUT);
        co.quads = quads.data();
        co.quad_capacity = capacity;
        co.quad_count = 0xDEADu;
        const rrc_result r = rrc_frame_classify(split.get(), &f, &co);
        if (count) *count = co.quad_count;
        return r;
    };
    auto resolve = [&]() {
        rrc_resolve_desc rd = rrc_host::rrc_struct<rrc_resolve_desc>(RRC_STRUCT_TYPE_RESOLVE_DESC);
        rd.channel_count = 1;
        rd.channels = &in;
        FrameResult r;
        BoundOutput o(r, channels, n, kUnwritten);
        EXPECT_EQ(rrc_frame_resolve(split.get(), &rd, &o.frame), RRC_SUCCESS) << rrc_last_error();
        return r;
    };
    auto expect_equal = [&](const FrameResult& a, const FrameResult& b, const char* what) {
        EXPECT_EQ(a.mask, b.mask) << what;
        EXPECT_EQ(a.age[0], b.age[0]) << what;
        EXPECT_EQ(std::memcmp(a.values[0].data(), b.values[0].data(), 4 * n * sizeof(float)), 0) << what << ": values bit for bit";
    };

    // Frame 0: every pixel misses (8 quads).
    uint32_t count = 0;
    const rrc_frame_desc f0 = frame(0, depth, clip);
    ASSERT_EQ(classify(f0, 8, &count), RRC_SUCCESS) << rrc_last_error();
    EXPECT_EQ(count, 8u);
    expect_equal(resolve(), fused.run(f0), "frame 0");

    // Frame 1: static, every pixel a HIT (nothing listed).  Then a different
    // frame whose classify fails: the right half resampled half a pixel
    // away (HITs with other values), the left half at another depth (misses: 4 quads).
    for (uint32_t i = 0; i < 4 * n; ++i) shade[i] = 1.0f - shade[i];
    const rrc_frame_desc f1 = frame(1, depth, clip);
    ASSERT_EQ(classify(f1, 8, &count), RRC_SUCCESS) << rrc_last_error();
    EXPECT_EQ(count, 0u);
    std::vector<float> depth_b = depth, clip_b = clip;
    for (uint32_t i = 0; i < n; ++i) {
        if (i % W < W / 2) depth_b[i] = clip_b[4 * i + 2] = 0.25f;  // expected 0.25, previous 0.5
        else clip_b[4 * i] += 1.0f / W;  // half a pixel in x
    }
    const rrc_frame_desc b = frame(1, depth_b, clip_b);
    EXPECT_EQ(classify(b, 3, &count), RRC_ERROR_SIZE_MISMATCH);
    EXPECT_EQ(count, 0xDEADu) << "a failed classify writes nothing";
    // Resolve completes frame 1 as classified first.
    expect_equal(resolve(), fused.run(f1), "frame 1 after a failed classify");
    // And history is frame 1's: frame 2 (static) still agrees.
    const rrc_frame_desc f2 = frame(2, depth, clip);
    ASSERT_EQ(classify(f2, 8, &count), RRC_SUCCESS) << rrc_last_error();
    expect_equal(resolve(), fused.run(f2), "frame 2");
}

// ---- A flat plane under CAMERA reprojection (depth 0.5, identity-like matrices).

constexpr int kW = 23, kH = 15, kN = kW * kH;  // odd: half quads at the right and bottom
constexpr int kQW = (kW + 1) / 2, kQH = (kH + 1) / 2, kQ = kQW * kQH;

TEST(ShadingCacheRefresh, OncePerPeriodFromNear2To40AndBalancedRandom) {
    const std::vector<rrc_channel_desc> channels = one_reuse();
    for_each_refresh_case(kW, kH, channels, [&](rrc_context_desc d, FlatPlane& flat, uint32_t n, uint64_t stride) {
        const rrc_refresh_policy policy = d.refresh_policy;
        if (policy == RRC_REFRESH_TILED && n == 8) d.refresh_tiles[0] = 4, d.refresh_tiles[1] = 2;
        Context ctx(d);
        ASSERT_TRUE(ctx);
        const uint64_t t0 = (1ull << 40) - 5;
        std::vector<float> previous = run_fused(ctx, channels, flat.frame(t0 - stride, 0, 0)).r.values[0];
        const rrc_ref::Params ref = rrc_ref::resolve(ctx.desc());
        OncePerPeriod periods(kN, n);
        for (uint32_t k = 0; k < 2 * n; ++k) {
            const uint64_t t = t0 + k * stride;
            for (int i = 0; i < kN; ++i) flat.shade[i] = (float)(1000 * k + i);
            const FusedRun r = run_fused(ctx, channels, flat.frame(t, 0, 0));
            expect_stats(r.r.mask, r.r.stats, r.refreshed, "static");
            std::set<int> due_quads;
            for (int i = 0; i < kN; ++i) {
                const bool refreshed = (r.r.mask[i] & RRC_MASK_REFRESHED) != 0;
                ASSERT_EQ(refreshed, rrc_ref::refresh_due(ref, i % kW, i / kW, t)) << "pixel " << i << " t " << t;
                ASSERT_TRUE(refreshed || (r.r.mask[i] & RRC_MASK_HIT)) << "a static scene hits everywhere";
                if (refreshed) {
                    periods.refreshed(i);
                    due_quads.insert(i % kW / 2 + kQW * (i / kW / 2));
                    EXPECT_EQ(r.r.values[0][i], flat.shade[i]);
                    EXPECT_EQ(r.r.age[0][i], 1u);
                } else {
                    EXPECT_EQ(r.r.values[0][i], previous[i]) << "a hit keeps the cached value";
                }
            }
            if (policy == RRC_REFRESH_RANDOM) {
                // Whole quads, floor(Q/n) or ceil(Q/n) of them.
                for (int q : due_quads)
                    for (int s = 0; s < 4; ++s) {
                        const int x = 2 * (q % kQW) + (s & 1), y = 2 * (q / kQW) + (s >> 1);
                        if (x < kW && y < kH) EXPECT_TRUE(r.r.mask[y * kW + x] & RRC_MASK_REFRESHED) << "quad " << q;
                    }
                EXPECT_GE((int)due_quads.size(), kQ / (int)n) << "t " << t;
                EXPECT_LE((int)due_quads.size(), (kQ + (int)n - 1) / (int)n) << "t " << t;
            }
            previous = r.r.values[0];
            ASSERT_NO_FATAL_FAILURE(periods.end_frame(k, t));
        }
    });
}

TEST(ShadingCacheRefresh, LifetimeAloneRefreshesAtAgeLUnderAPan) {
    for (uint32_t L : {1u, 2u, 4u}) {
        SCOPED_TRACE("L " + std::to_string(L));
        std::vector<rrc_channel_desc> channels = one_reuse();
        FlatPlane flat(kW, kH);
        rrc_context_desc d = flat.context(channels);
        d.max_lifetime = L;  // no policy: only the lifetime (and empty histories) refresh
        Context ctx(d);
        ASSERT_TRUE(ctx);
        std::vector<float> pv;
        std::vector<uint16_t> pa;
        int at_age_l = 0;
        for (int t = 0; t < 3 * (int)L + 4; ++t) {
            for (int i = 0; i < kN; ++i) flat.shade[i] = (float)(1000 * t + i);
            // The surface moves 1 pixel left a frame: pixel x shows what x+1 showed.
            const FusedRun r = run_fused(ctx, channels, flat.frame((uint64_t)t, -1.0 * t, t ? -1.0 * (t - 1) : 0.0));
            expect_stats(r.r.mask, r.r.stats, r.refreshed, "pan");
            for (int i = 0; i < kN; ++i) {
                const int x = i % kW, y = i / kW;
                ASSERT_LE(r.r.age[0][i], L) << "no value used in more than L frames";
                if (t == 0 || x == kW - 1) {
                    EXPECT_FALSE(r.r.mask[i] & (RRC_MASK_HIT | RRC_MASK_REFRESHED)) << "t " << t << " x " << x;
                    continue;
                }
                const int src = i + 1;
                if (pa[src] >= L) {
                    ++at_age_l;
                    ASSERT_TRUE(r.r.mask[i] & RRC_MASK_REFRESHED) << "t " << t << " pixel " << x << "," << y << " source age " << pa[src];
                    EXPECT_EQ(r.r.values[0][i], flat.shade[i]);
                    EXPECT_EQ(r.r.age[0][i], 1u);
                } else {
                    ASSERT_TRUE(r.r.mask[i] & RRC_MASK_HIT) << "t " << t << " pixel " << x << "," << y << " source age " << pa[src];
                    EXPECT_EQ(r.r.values[0][i], pv[src]);
                    EXPECT_EQ(r.r.age[0][i], pa[src] + 1);
                }
            }
            pv = r.r.values[0];
            pa = r.r.age[0];
        }
        EXPECT_GT(at_age_l, kN) << "the lifetime must have fired";
    }
}

}  // namespace
