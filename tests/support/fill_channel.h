// A channel description with the spatial fill set or cleared
// (docs/CONVENTIONS.md, "The spatial fill"): the kernel tests' fill channels
// and their twins without a fill, whose history is the one the fill reads.
#pragma once

#include <rrc/rrc.h>

#include <cstdint>

namespace rrc_test {

inline rrc_channel_desc filled(rrc_channel_desc d, uint32_t T, uint32_t r, float P) {
    d.fill_age = T;
    d.fill_radius = r;
    d.fill_prior = P;
    return d;
}

inline rrc_channel_desc without_fill(rrc_channel_desc d) {
    d.fill_age = 0;
    d.fill_radius = 0;
    d.fill_depth_tolerance = 0.0f;
    d.fill_prior = 0.0f;
    return d;
}

}  // namespace rrc_test
