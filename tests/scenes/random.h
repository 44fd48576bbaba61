// Deterministic pseudo-random numbers for the analytic scenes.
//
// Why a hash and not a stateful generator: every pixel's noise must depend only
// on (seed, frame, pixel, stream), so a frame can be re-rendered alone, in any
// order, and the kernel and the CPU reference see identical inputs.
#pragma once

#include <cstdint>

namespace rrc_scene {

// splitmix64 finaliser: a good 64-bit mixer (Steele, Lea, Flood 2014).
inline uint64_t mix64(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// Hash of (seed, frame, pixel, stream).  Distinct streams give independent
// numbers for the same pixel (noise of each component, NaN injection, ...).
inline uint64_t hash4(uint64_t seed, int64_t frame, uint64_t pixel, uint64_t stream) {
    uint64_t h = mix64(seed);
    h = mix64(h ^ static_cast<uint64_t>(frame));
    h = mix64(h ^ pixel);
    return mix64(h ^ (stream * 0xD1B54A32D192ED03ull));
}

// Uniform double in [0, 1) with 53 random bits.
inline double uniform01(uint64_t h) { return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0); }

// Radical inverse of index in the given base: the Halton sequence in [0, 1).
// Exact in double for the small indices used (finite sums of b^-k).
inline double halton(uint32_t index, uint32_t base) {
    double result = 0.0, f = 1.0;
    while (index > 0) {
        f /= base;
        result += f * (index % base);
        index /= base;
    }
    return result;
}

}  // namespace rrc_scene
