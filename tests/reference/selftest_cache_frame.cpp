// Whole frames of the reference with REUSE channels (docs/CONVENTIONS.md,
// "The shading cache"), hand-computed on an 8x6 static scene under an
// identity CAMERA where every pixel passes the hit test: the REUSE table, the
// empty-history and lifetime refreshes, the policy clocked by the frame
// descriptor's frame_index, HIT / REFRESHED bits and the counts.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "cache.h"
#include "selftest_scene.h"

using rrc_ref::FrameResult;
using rrc_ref::PreviousFrame;
using rrc_ref_test::Scene;

namespace {

// c0: REUSE fp32 nearest, c1: FIXED lambda 0.5 (accumulating), c2 (optional): REUSE.
struct Cache {
    Scene s{8, 6, RRC_DEPTH_MODE_STANDARD, RRC_REPROJECTION_CAMERA};
    explicit Cache(bool two_reuse = false) {
        s.add_channel(1, 0.0f, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_NEAREST);
        s.add_channel(1, 0.5f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_NEAREST);
        if (two_reuse) s.add_channel(1, 0.0f, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_NEAREST);
        for (size_t k = 0; k < s.size(); ++k)
            for (auto& c : s.samples) c[k] = 100.0f + k;
    }
    PreviousFrame prev(uint16_t age) const {
        std::vector<std::vector<float>> h;
        for (size_t c = 0; c < s.channel_descs.size(); ++c) {
            h.emplace_back(s.size());
            for (size_t k = 0; k < s.size(); ++k) h.back()[k] = 10.0f + k;
        }
        return s.previous(h, age);
    }
};

void expect_counts(const FrameResult& r, uint64_t hits, uint64_t refreshed, uint64_t misses) {
    EXPECT_EQ(r.stats.hits, hits);
    EXPECT_EQ(r.refreshed, refreshed);
    EXPECT_EQ(r.stats.misses, misses);
}

}  // namespace

TEST(CacheFrame, ReuseHitKeepsTheValueAndIgnoresTheSample) {
    Cache c;
    for (size_t k = 0; k < c.s.size(); ++k) c.s.samples[0][k] = NAN;  // never read on a HIT
    const FrameResult r = c.s.run(c.prev(3));
    for (size_t k = 0; k < c.s.size(); ++k) {
        EXPECT_EQ(r.mask[k], RRC_MASK_HIT) << k;  // no INVALID_SAMPLE
        EXPECT_EQ(r.channels[0].out[k], 10.0 + k);
        EXPECT_EQ(r.channels[0].age[k], 4);
        EXPECT_EQ(r.channels[1].out[k], 0.5 * (10.0 + k) + 0.5 * (100.0 + k));  // the accumulating channel blends
    }
    expect_counts(r, c.s.size(), 0, 0);
    EXPECT_EQ(r.stats.invalid_samples, 0u);
}

TEST(CacheFrame, ReuseAgeStopsAtTheCap) {
    Cache c;
    c.s.channel_descs[0].age_cap = 5;
    const FrameResult r = c.s.run(c.prev(5));
    for (size_t k = 0; k < c.s.size(); ++k) EXPECT_EQ(r.channels[0].age[k], 5) << k;
}

TEST(CacheFrame, AnEmptyReuseHistoryRefreshes) {
    Cache c;
    PreviousFrame p = c.prev(3);
    const size_t k0 = c.s.at(5, 2);
    p.channels[0].age[k0] = 0;            // its last sample was invalid
    p.channels[1].age[c.s.at(1, 1)] = 0;  // an accumulating channel's empty history refreshes nothing
    const FrameResult r = c.s.run(p);
    for (size_t k = 0; k < c.s.size(); ++k) {
        if (k == k0) {
            EXPECT_EQ(r.mask[k], RRC_MASK_REFRESHED);
            EXPECT_EQ(r.channels[0].out[k], 100.0 + k);
            EXPECT_EQ(r.channels[0].age[k], 1);
            EXPECT_EQ(r.channels[1].out[k], 0.5 * (10.0 + k) + 0.5 * (100.0 + k)) << "the accumulating channel still takes the hit";
            EXPECT_EQ(r.channels[1].age[k], 4);
        } else {
            EXPECT_EQ(r.mask[k], RRC_MASK_HIT) << k;
        }
    }
    expect_counts(r, c.s.size() - 1, 1, 0);
}

TEST(CacheFrame, MaxLifetimeUsesTheLargestReuseAge) {
    for (uint16_t age : {1, 3, 4, 7}) {
        Cache c(true);
        c.s.ctx.max_lifetime = 4;
        PreviousFrame p = c.prev(1);
        for (auto& a : p.channels[2].age) a = age;  // A_max over the REUSE channels
        for (auto& a : p.channels[1].age) a = 9;    // accumulating ages do not count
        const FrameResult r = c.s.run(p);
        const bool refresh = age >= 4;
        for (size_t k = 0; k < c.s.size(); ++k) {
            EXPECT_EQ(r.mask[k], refresh ? RRC_MASK_REFRESHED : RRC_MASK_HIT) << "age " << age;
            EXPECT_EQ(r.channels[0].age[k], refresh ? 1 : 2);
            EXPECT_EQ(r.channels[2].age[k], refresh ? 1 : age + 1);
        }
        expect_counts(r, refresh ? 0 : c.s.size(), refresh ? c.s.size() : 0, 0);
    }
}

TEST(CacheFrame, ARefreshWithAnInvalidSampleStoresNothing) {
    Cache c;
    c.s.ctx.max_lifetime = 2;
    const size_t k0 = c.s.at(3, 4);
    c.s.samples[0][k0] = NAN;
    const FrameResult r = c.s.run(c.prev(2));  // every pixel at the lifetime
    EXPECT_EQ(r.mask[k0], RRC_MASK_REFRESHED | RRC_MASK_INVALID_SAMPLE);
    EXPECT_EQ(r.channels[0].out[k0], 0.0);
    EXPECT_EQ(r.channels[0].age[k0], 0);
    expect_counts(r, 0, c.s.size(), 0);
    EXPECT_EQ(r.stats.invalid_samples, 1u);
}

TEST(CacheFrame, MissAndBackgroundFollowTheTable) {
    Cache c;
    c.s.depth[c.s.at(0, 0)] = 1.0f;  // STANDARD background
    c.s.depth[c.s.at(1, 0)] = 1.0f;
    c.s.samples[0][c.s.at(1, 0)] = NAN;
    c.s.samples[0][c.s.at(2, 0)] = NAN;
    const FrameResult r = c.s.run(PreviousFrame{});  // no previous frame: misses
    EXPECT_EQ(r.mask[c.s.at(0, 0)], RRC_MASK_BACKGROUND);
    EXPECT_EQ(r.channels[0].out[c.s.at(0, 0)], 100.0);
    EXPECT_EQ(r.channels[0].age[c.s.at(0, 0)], 0);
    EXPECT_EQ(r.mask[c.s.at(1, 0)], RRC_MASK_BACKGROUND | RRC_MASK_INVALID_SAMPLE);
    EXPECT_EQ(r.channels[0].out[c.s.at(1, 0)], 0.0);
    EXPECT_EQ(r.mask[c.s.at(2, 0)], RRC_MASK_INVALID_SAMPLE);
    EXPECT_EQ(r.channels[0].out[c.s.at(2, 0)], 0.0);
    EXPECT_EQ(r.channels[0].age[c.s.at(2, 0)], 0);
    EXPECT_EQ(r.mask[c.s.at(3, 0)], 0);
    EXPECT_EQ(r.channels[0].out[c.s.at(3, 0)], 103.0);
    EXPECT_EQ(r.channels[0].age[c.s.at(3, 0)], 1);
    EXPECT_EQ(r.stats.background, 2u);
    expect_counts(r, 0, 0, c.s.size() - 2);
    EXPECT_EQ(rrc_ref::listed_quads(r.mask, c.s.W, c.s.H).size(), 12u);
}

TEST(CacheFrame, TiledReadsTheFrameIndexIn64Bit) {
    Cache c;
    c.s.ctx.refresh_policy = RRC_REFRESH_TILED;
    c.s.ctx.refresh_period = 4;                // {0, 0}: 4 vertical strips of 2 columns
    c.s.frame.frame_index = (1ull << 40) + 1;  // phase 1: tile 3 (x = 6, 7) is due
    const FrameResult r = c.s.run(c.prev(3));
    for (int j = 0; j < c.s.H; ++j)
        for (int i = 0; i < c.s.W; ++i) EXPECT_EQ(r.mask[c.s.at(i, j)], i >= 6 ? RRC_MASK_REFRESHED : RRC_MASK_HIT) << i << "," << j;
    expect_counts(r, 36, 12, 0);
    // The listed quads: x = 6..7 is quad column 3.
    EXPECT_EQ(rrc_ref::listed_quads(r.mask, c.s.W, c.s.H), (std::set<uint32_t>{3u, 3u | 1u << 16, 3u | 2u << 16}));
}

TEST(CacheFrame, RandomRefreshesWholeQuadsOncePerPeriod) {
    for (unsigned n : {2u, 3u, 4u, 5u}) {
        Cache c;
        c.s.ctx.refresh_policy = RRC_REFRESH_RANDOM;
        c.s.ctx.refresh_period = n;
        std::vector<int> count(c.s.size(), 0);
        const unsigned Q = 12;  // 4 x 3 quads
        for (uint64_t t = (1ull << 40) - 2; t < (1ull << 40) - 2 + n; ++t) {
            c.s.frame.frame_index = t;
            const FrameResult r = c.s.run(c.prev(3));
            std::set<size_t> quads;
            for (size_t k = 0; k < c.s.size(); ++k)
                if (r.mask[k] & RRC_MASK_REFRESHED) {
                    ++count[k];
                    quads.insert(k % c.s.W / 2 + 4 * (k / c.s.W / 2));
                }
            EXPECT_EQ(r.refreshed, 4 * quads.size()) << "whole quads (the frame has no half quads)";
            EXPECT_GE(quads.size(), Q / n) << "n " << n << " t " << t;
            EXPECT_LE(quads.size(), (Q + n - 1) / n) << "n " << n << " t " << t;
        }
        for (size_t k = 0; k < c.s.size(); ++k) EXPECT_EQ(count[k], 1) << "n " << n << " pixel " << k;
    }
}
