// The reference's shading-cache rules against hand-computed cases and the
// properties docs/CONVENTIONS.md promises: each policy picks every pixel
// exactly once in any n consecutive frame indices, RANDOM a balanced share
// of the quads each frame, and the list holds exactly the quads with a pixel
// that is not a HIT.
#include "cache.h"
#include "rrc_descs.h"

#include <gtest/gtest.h>

#include <vector>

namespace {

rrc_ref::Params params(int w, int h, rrc_refresh_policy policy, unsigned n, unsigned gx = 0, unsigned gy = 0) {
    std::vector<rrc_channel_desc> ch{rrc_host::channel("c", 1, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_REUSE)};
    rrc_context_desc d = rrc_host::context_desc((uint32_t)w, (uint32_t)h, ch);
    d.refresh_policy = policy;
    d.refresh_period = n;
    d.refresh_tiles[0] = gx;
    d.refresh_tiles[1] = gy;
    return rrc_ref::resolve(d);
}

TEST(ReferenceCache, HashValues) {
    // x ^= x >> 16; x *= 0x7feb352d; x ^= x >> 15; x *= 0x846ca68b; x ^= x >> 16 (mod 2^32), by hand in Python.
    EXPECT_EQ(rrc_ref::cache_hash(0), 0u);
    EXPECT_EQ(rrc_ref::cache_hash(1), 1753845952u);
    EXPECT_EQ(rrc_ref::cache_hash(12345), 2435775735u);
}

TEST(ReferenceCache, TiledPicksTheStatedTile) {
    const rrc_ref::Params p = params(64, 32, RRC_REFRESH_TILED, 32, 8, 4);  // the SVO seed's 8x4 tiles, 8x8 pixels each
    // Pixel (9, 9): tile (1, 1), i = 1 + 8 * 1 = 9, due when (t + 9) mod 32 = 0.
    for (uint64_t t = 0; t < 64; ++t) EXPECT_EQ(rrc_ref::refresh_due(p, 9, 9, t), (t + 9) % 32 == 0) << t;
    // The clock is 64-bit: t = 2^40 + 23 is 23 mod 32.
    EXPECT_TRUE(rrc_ref::refresh_due(p, 9, 9, (1ull << 40) + 23));
    EXPECT_TRUE(rrc_ref::refresh_due(p, 63, 31, 32 * 1000 + 1));         // tile 31
    const rrc_ref::Params strips = params(10, 4, RRC_REFRESH_TILED, 4);  // {0, 0}: {n, 1}, vertical strips
    EXPECT_EQ(strips.refresh_tiles[0], 4u);
    EXPECT_TRUE(rrc_ref::refresh_due(strips, 9, 3, 1));  // floor(9 * 4 / 10) = 3: due when (t + 3) mod 4 = 0
}

TEST(ReferenceCache, EveryPixelOnceInAnyNConsecutiveFrames) {
    for (rrc_refresh_policy policy : {RRC_REFRESH_TILED, RRC_REFRESH_RANDOM})
        for (unsigned n : {1u, 2u, 3u, 4u, 8u, 32u}) {
            const rrc_ref::Params p = policy == RRC_REFRESH_TILED && n == 32 ? params(37, 22, policy, n, 8, 4) : params(37, 22, policy, n);
            for (uint64_t t0 : {uint64_t(0), uint64_t((1ull << 40) - 3)}) {
                for (int y = 0; y < 22; ++y)
                    for (int x = 0; x < 37; ++x) {
                        int picked = 0;
                        for (uint64_t t = t0; t < t0 + n; ++t) picked += rrc_ref::refresh_due(p, x, y, t) ? 1 : 0;
                        ASSERT_EQ(picked, 1) << "policy " << policy << " n " << n << " pixel " << x << "," << y;
                    }
            }
        }
}

TEST(ReferenceCache, RandomRefreshesABalancedShareOfQuads) {
    const int W = 38, H = 22;  // 19 x 11 = 209 quads
    const unsigned Q = 19 * 11;
    for (unsigned n : {2u, 4u, 8u}) {
        const rrc_ref::Params p = params(W, H, RRC_REFRESH_RANDOM, n);
        for (uint64_t t = 0; t < 2 * n; ++t) {
            unsigned due = 0;
            for (int qy = 0; qy < H / 2; ++qy)
                for (int qx = 0; qx < W / 2; ++qx) {
                    const bool d = rrc_ref::refresh_due(p, 2 * qx, 2 * qy, t);
                    // the whole quad together
                    EXPECT_EQ(d, rrc_ref::refresh_due(p, 2 * qx + 1, 2 * qy + 1, t));
                    due += d ? 1 : 0;
                }
            EXPECT_GE(due, Q / n) << "n " << n << " t " << t;
            EXPECT_LE(due, (Q + n - 1) / n) << "n " << n << " t " << t;
        }
    }
}

TEST(ReferenceCache, ListedQuadsAreThoseWithANonHit) {
    const int W = 5, H = 3;  // quads 3 x 2; the last column and row are half quads
    std::vector<uint8_t> mask(W * H, RRC_MASK_HIT);
    mask[0 * W + 1] = 0;                    // a miss in quad (0, 0)
    mask[2 * W + 4] = RRC_MASK_REFRESHED;   // quad (2, 1), a half quad
    mask[1 * W + 2] = RRC_MASK_BACKGROUND;  // quad (1, 0)
    const std::set<uint32_t> q = rrc_ref::listed_quads(mask, W, H);
    EXPECT_EQ(q, (std::set<uint32_t>{0u, 1u, 2u | 1u << 16}));
}

}  // namespace
