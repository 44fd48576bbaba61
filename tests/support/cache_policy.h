// Test support: a shading-cache refresh configuration (docs/CONVENTIONS.md,
// "Refresh policies") as a test parameter, and its members in a context
// descriptor.
#pragma once

#include <rrc/rrc.h>

namespace rrc_test {

struct Policy {
    const char* name;
    rrc_refresh_policy policy;
    uint32_t period, tiles_x, tiles_y, lifetime;
};

inline void apply(const Policy& p, rrc_context_desc& d) {
    d.refresh_policy = p.policy;
    d.refresh_period = p.period;
    d.refresh_tiles[0] = p.tiles_x;
    d.refresh_tiles[1] = p.tiles_y;
    d.max_lifetime = p.lifetime;
}

}  // namespace rrc_test
