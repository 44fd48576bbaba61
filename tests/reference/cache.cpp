#include "cache.h"

#include <rrc/rrc.h>

namespace rrc_ref {

uint32_t cache_hash(uint32_t x) {
    x ^= x >> 16;
    x = (uint32_t)((uint64_t)x * 0x7feb352dull);
    x ^= x >> 15;
    x = (uint32_t)((uint64_t)x * 0x846ca68bull);
    x ^= x >> 16;
    return x;
}

bool refresh_due(const Params& p, int x, int y, uint64_t t) {
    const uint64_t n = p.refresh_period;
    if (p.refresh_policy == RRC_REFRESH_TILED) {
        const uint64_t tx = (uint64_t)x * p.refresh_tiles[0] / (uint64_t)p.width;
        const uint64_t ty = (uint64_t)y * p.refresh_tiles[1] / (uint64_t)p.height;
        const uint64_t tile = tx + p.refresh_tiles[0] * ty;
        return (t % n + tile % n) % n == 0;  // (t + tile) mod n without 64-bit overflow
    }
    if (p.refresh_policy == RRC_REFRESH_RANDOM) {
        const uint64_t quads_a_row = ((uint64_t)p.width + 1) / 2;
        const uint64_t q = (uint64_t)(x / 2) + quads_a_row * (uint64_t)(y / 2);
        const uint64_t block = q / n, j = q % n;
        const uint64_t d = (j + cache_hash((uint32_t)block) % n) % n;
        return (t % n + d) % n == 0;
    }
    return false;
}

std::set<uint32_t> listed_quads(const std::vector<uint8_t>& mask, int width, int height) {
    std::set<uint32_t> quads;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            if (!(mask[(size_t)y * width + x] & RRC_MASK_HIT)) quads.insert((uint32_t)(x / 2) | (uint32_t)(y / 2) << 16);
    return quads;
}

}  // namespace rrc_ref
