// The shading cache's rules, re-derived from docs/CONVENTIONS.md ("The
// shading cache"): which hits a REUSE channel refreshes (TILED and RANDOM
// clocked by the frame index in 64-bit, the maximum lifetime, empty
// histories) and which 2x2 quads classify lists.  Shares no code with
// compute/rrc_cache.glsl.
#ifndef RRC_REFERENCE_CACHE_H
#define RRC_REFERENCE_CACHE_H

#include "params.h"

#include <cstdint>
#include <set>
#include <vector>

namespace rrc_ref {

// The refresh policy picks pixel (x, y) at frame index t (no lifetime, no ages).
bool refresh_due(const Params& p, int x, int y, uint64_t t);

// The quads (x | y << 16) holding a pixel inside the frame without RRC_MASK_HIT.
std::set<uint32_t> listed_quads(const std::vector<uint8_t>& mask, int width, int height);

// CONVENTIONS.md's 32-bit hash.
uint32_t cache_hash(uint32_t x);

}  // namespace rrc_ref

#endif
