// The shading cache (docs/CONVENTIONS.md, "The shading cache") against the
// independent double-precision reference (tests/reference/cache.h):
//   - REUSE and accumulating channels under TILED, RANDOM and no policy, with
//     and without a maximum lifetime, on a moving analytic scene, fused
//     (rrc_frame_run) and split (rrc_frame_classify + rrc_frame_resolve, the
//     REUSE samples NaN outside the listed quads): mask, listed quads (as a
//     set), counts, values and ages, one frame at a time from the kernel's
//     own previous state (as tests/kernels/kernel_reference_test.cpp);
//   - on a static scene each policy refreshes every pixel exactly once every
//     n frames, also with frame indices past 2^32 that skip by 3;
//   - under a camera pan the maximum lifetime forces the refresh at the
//     stated age, which no policy would.
// Every context runs under the validation layer (support/rrc_test_context.h).
#include "reference/cache.h"
#include "reference/rrc_reference.h"
#include "support/cache_policy.h"
#include "support/flat_plane.h"
#include "support/kernel_state.h"
#include "support/rrc_test_context.h"
#include "support/scene_frames.h"
#include "support/split_frame.h"
#include "support/tolerance.h"

#include <cmath>
#include <set>

using namespace rrc_test;

namespace {

const Policy kPolicies[] = {
    {"tiled_4", RRC_REFRESH_TILED, 4, 2, 2, 0},
    {"random_4_lifetime_3", RRC_REFRESH_RANDOM, 4, 0, 0, 3},
    {"none_lifetime_2", RRC_REFRESH_NONE, 0, 0, 0, 2},
};

std::vector<rrc_channel_desc> cache_channels() {
    return {channel("shade", 4, 0.0f, RRC_HISTORY_FP16, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_BILINEAR),
            channel("ao", 1, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_NEAREST),
            channel("pcf", 1, 0.6f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR)};
}

// One frame's outputs through the split path: classify, the host's samples
// only at the listed quads (NaN elsewhere for REUSE channels), resolve.
struct SplitResult {
    FrameResult out;
    std::set<uint32_t> quads;
    std::vector<uint8_t> classified;
    rrc_frame_stats classify_stats{};
    uint64_t refreshed = 0;
};

SplitResult run_split(Context& ctx, const std::vector<rrc_channel_desc>& channels, SceneFrameInputs& in, int W, int H) {
    SplitResult s;
    Classification cl((uint32_t)W, (uint32_t)H);
    EXPECT_EQ(cl.run(ctx.get(), geometry_of(in.desc)), RRC_SUCCESS) << rrc_last_error();
    s.classified = cl.mask;
    s.quads = cl.listed();
    EXPECT_EQ(s.quads.size(), cl.out.quad_count) << "a quad listed twice";
    s.classify_stats = cl.out.stats;
    s.refreshed = cl.out.refreshed;

    HostSamples host(channels, in.desc, s.quads, W, H);
    BoundOutput o(s.out, channels, (size_t)W * H);
    EXPECT_EQ(rrc_frame_resolve(ctx.get(), &host.desc, &o.frame), RRC_SUCCESS) << rrc_last_error();
    s.out.stats = o.frame.stats;
    return s;
}

using Param = std::tuple<Policy, bool>;  // policy, split path

class CacheVsReference : public ::testing::TestWithParam<Param> {};

TEST_P(CacheVsReference, OneFrameAtATime) {
    const Policy& pol = std::get<0>(GetParam());
    const bool split = std::get<1>(GetParam());
    const int W = 64, H = 48, frames = 9;
    std::vector<rrc_channel_desc> channels = cache_channels();
    rrc_scene::SceneConfig sc = scene_config(W, H, RRC_DEPTH_MODE_REVERSED);
    sc.jitter = true;
    rrc_scene::Scene scene(sc);
    rrc_context_desc desc = scene_context_desc(scene.config(), RRC_REPROJECTION_PREV_CLIP, channels);
    apply(pol, desc);
    Context ctx(desc);
    ASSERT_TRUE(ctx);

    rrc_ref::PreviousFrame prev;
    int64_t compared = 0, flagged = 0, refreshed = 0, hits = 0, reused = 0;
    for (int t = 0; t < frames; ++t) {
        SceneFrameInputs in;
        in.frame = scene.render(t);
        make_frame_inputs(in, RRC_REPROJECTION_PREV_CLIP, channels);
        in.desc.frame_index = (1ull << 33) + (uint64_t)t;  // the clock is 64-bit
        FrameResult k;
        if (split) {
            SplitResult s = run_split(ctx, channels, in, W, H);
            k = s.out;
            // The list is exactly the quads of the kernel's own mask without HIT.
            EXPECT_EQ(s.quads, rrc_ref::listed_quads(s.classified, W, H)) << "frame " << t;
            for (size_t i = 0; i < s.classified.size(); ++i)
                ASSERT_EQ(s.classified[i], k.mask[i] & ~RRC_MASK_INVALID_SAMPLE) << "resolve keeps classify's mask, pixel " << i;
            EXPECT_EQ(s.classify_stats.hits, k.stats.hits);
            EXPECT_EQ(s.classify_stats.misses, k.stats.misses);
        } else {
            k = ctx.run(in.desc);
        }
        const rrc_ref::FrameResult r = rrc_ref::run_frame(ctx.desc(), prev, in.desc);
        const size_t n = (size_t)W * H;
        std::set<uint32_t> flagged_quads;
        for (size_t i = 0; i < n; ++i) {
            // The hit decision, and the ages the refresh reads, may differ within fp32 error there.
            if (r.near_threshold[i] || r.near_nearest_edge[i]) {
                ++flagged;
                flagged_quads.insert((uint32_t)(i % W / 2) | (uint32_t)(i / W / 2) << 16);
                continue;
            }
            ++compared;
            refreshed += (r.mask[i] & RRC_MASK_REFRESHED) ? 1 : 0;
            hits += (r.mask[i] & RRC_MASK_HIT) ? 1 : 0;
            ASSERT_EQ(k.mask[i], r.mask[i]) << pol.name << " frame " << t << " pixel (" << i % W << "," << i / W << ")";
            for (size_t ch = 0; ch < channels.size(); ++ch) {
                EXPECT_EQ(k.age[ch][i], r.channels[ch].age[i]) << pol.name << " frame " << t << " pixel " << i << " channel " << ch;
                const uint32_t m = channels[ch].components;
                const bool fp16 = channels[ch].precision == RRC_HISTORY_FP16;
                for (uint32_t q = 0; q < m; ++q) {
                    const double kv = k.values[ch][m * i + q], rv = r.channels[ch].out[m * i + q];
                    const double spread = prev.valid ? history_spread(prev.channels[ch].history, m, q, W, H, r.uv_prev_x[i], r.uv_prev_y[i],
                                                                      in.desc.prev_jitter)
                                                     : 0.0;
                    const double tol = arithmetic_tolerance(rv, r.channels[ch].exact[m * i + q], fp16) + position_tolerance(spread, W, H);
                    EXPECT_LE(std::fabs(kv - rv), tol) << pol.name << " frame " << t << " pixel " << i << " channel " << ch;
                }
            }
            if ((r.mask[i] & RRC_MASK_HIT) && r.channels[0].age[i] > 1) ++reused;
        }
        if (split) {
            // Away from flagged pixels the kernel lists exactly the reference's quads.
            const std::set<uint32_t> want = rrc_ref::listed_quads(r.mask, W, H);
            const std::set<uint32_t> got = rrc_ref::listed_quads(k.mask, W, H);
            for (uint32_t q : want)
                if (!flagged_quads.count(q)) EXPECT_TRUE(got.count(q)) << "frame " << t << " quad " << (q & 0xFFFF) << "," << (q >> 16);
            for (uint32_t q : got)
                if (!flagged_quads.count(q)) EXPECT_TRUE(want.count(q)) << "frame " << t << " quad " << (q & 0xFFFF) << "," << (q >> 16);
        }
        prev = kernel_state(in.frame.depth, k);
    }
    std::printf("%s %s: compared %lld flagged %lld hits %lld refreshed %lld reused %lld\n", pol.name, split ? "split" : "fused",
                (long long)compared, (long long)flagged, (long long)hits, (long long)refreshed, (long long)reused);
    EXPECT_GT(refreshed, 0) << "the comparison must cover refreshes";
    EXPECT_GT(reused, 0) << "the comparison must cover values reused over frames";
    EXPECT_GT(compared, (int64_t)W * H * frames * 8 / 10);
}

INSTANTIATE_TEST_SUITE_P(Policies, CacheVsReference, ::testing::Combine(::testing::ValuesIn(kPolicies), ::testing::Bool()),
                         [](const ::testing::TestParamInfo<Param>& i) {
                             return std::string(std::get<0>(i.param).name) + (std::get<1>(i.param) ? "_split" : "_fused");
                         });

// ---- A flat plane under CAMERA reprojection: every texel centre lands on one.

constexpr int kW = 21, kH = 13, kN = kW * kH;  // odd: half quads at the right and bottom

TEST(CacheRefresh, EveryPixelOnceEveryNFramesOnAStaticScene) {
    const std::vector<rrc_channel_desc> channels = one_reuse();
    for_each_refresh_case(kW, kH, channels, [](const rrc_context_desc& d, FlatPlane& flat, uint32_t n, uint64_t stride) {
        Context ctx(d);
        ASSERT_TRUE(ctx);
        const uint64_t t0 = (1ull << 32) - 2;    // indices cross 2^32
        ctx.run(flat.frame(t0 - stride, 0, 0));  // fills the cache
        const rrc_ref::Params ref = rrc_ref::resolve(ctx.desc());
        OncePerPeriod periods(kN, n);
        for (uint32_t k = 0; k < 2 * n; ++k) {
            const uint64_t t = t0 + k * stride;
            for (int i = 0; i < kN; ++i) flat.shade[i] = (float)(1000 * k + i);
            const FrameResult r = ctx.run(flat.frame(t, 0, 0));
            for (int i = 0; i < kN; ++i) {
                const bool refreshed = (r.mask[i] & RRC_MASK_REFRESHED) != 0;
                ASSERT_EQ(refreshed, rrc_ref::refresh_due(ref, i % kW, i / kW, t)) << "pixel " << i << " frame " << t;
                ASSERT_EQ(refreshed || (r.mask[i] & RRC_MASK_HIT), true) << "a static scene hits everywhere";
                if (refreshed) {
                    periods.refreshed(i);
                    EXPECT_EQ(r.values[0][i], flat.shade[i]) << "a refresh takes the new value";
                    EXPECT_EQ(r.age[0][i], 1u);
                }
            }
            ASSERT_NO_FATAL_FAILURE(periods.end_frame(k, t));
        }
    });
}

TEST(CacheRefresh, MaxLifetimeRefreshesAtTheStatedAgeUnderACameraPan) {
    const uint32_t L = 3;
    std::vector<rrc_channel_desc> channels = one_reuse();
    FlatPlane flat(kW, kH);
    rrc_context_desc d = flat.context(channels);
    d.max_lifetime = L;
    // A TILED policy that aliases with the pan: the surface moves one tile
    // (kW / 7 = 3 pixels) to the left a frame while the tiles' turn moves one
    // to the right, so a surface point keeps its phase and most never meet
    // their tile's turn; the lifetime must still bound every value's age.
    d.refresh_policy = RRC_REFRESH_TILED;
    d.refresh_period = 7;
    Context ctx(d);
    ASSERT_TRUE(ctx);
    rrc_ref::PreviousFrame prev;
    int lifetime_refreshes = 0, flagged = 0;
    std::vector<float> previous_values;
    std::vector<uint16_t> previous_age;
    const int frames = 16;
    for (int t = 0; t < frames; ++t) {
        for (int i = 0; i < kN; ++i) flat.shade[i] = (float)(1000 * t + i);
        const rrc_frame_desc f = flat.frame((uint64_t)t, -3.0 * t, t ? -3.0 * (t - 1) : 0.0);
        const FrameResult r = ctx.run(f);
        // The geometry is exact by construction (depth 0.5, whole-pixel pans): the
        // reference flags only pixels exactly on a threshold (error_scale 0).
        rrc_ref::Options exact;
        exact.error_scale = 0.0;
        const rrc_ref::FrameResult ref = rrc_ref::run_frame(ctx.desc(), prev, f, exact);
        const rrc_ref::Params p = rrc_ref::resolve(ctx.desc());
        for (int i = 0; i < kN; ++i) {
            const int x = i % kW, y = i / kW;
            if (ref.near_threshold[i] || ref.near_nearest_edge[i]) {
                ++flagged;
                continue;
            }
            ASSERT_EQ(r.mask[i], ref.mask[i]) << "frame " << t << " pixel " << x << "," << y;
            ASSERT_EQ(r.age[0][i], ref.channels[0].age[i]);
            ASSERT_LE(r.age[0][i], L) << "no value is used in more than L frames";
            if (t == 0 || x >= kW - 3) continue;  // the first frame, and what the pan brings in, miss
            const int src = i + 3;                // where the pan brings this pixel's surface from
            const bool due = rrc_ref::refresh_due(p, x, y, (uint64_t)t);
            if (r.mask[i] & RRC_MASK_HIT) {
                EXPECT_LT(previous_age[src], L);
                EXPECT_EQ(r.values[0][i], previous_values[src]) << "a hit reuses the value unchanged";
                EXPECT_EQ(r.age[0][i], previous_age[src] + 1);
            } else {
                ASSERT_TRUE(r.mask[i] & RRC_MASK_REFRESHED) << "frame " << t << " pixel " << x << "," << y;
                EXPECT_TRUE(due || previous_age[src] >= L);
                if (!due) ++lifetime_refreshes;
            }
        }
        previous_values = r.values[0];
        previous_age = r.age[0];
        prev = rrc_ref::as_previous(ctx.desc(), f, ref);
        prev.channels[0].history = r.values[0];
        prev.channels[0].age = r.age[0];
    }
    EXPECT_GT(lifetime_refreshes, kN) << "the lifetime, not the policy, must have forced refreshes";
    EXPECT_LT(flagged, kN * frames / 20) << "pixels within fp32 error of a decision";
}

}  // namespace
