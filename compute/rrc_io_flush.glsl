// The counted image operations (rrc_io.glsl) of one pixel into the statistics buffer
// (u_stats: RRC_BINDING_STATS), for the passes that count: the frame's and the fill's.
#ifndef RRC_IO_FLUSH_GLSL
#define RRC_IO_FLUSH_GLSL

#include "rrc_io.glsl"

// A pixel's counts into the buffer, when the pixel is inside the frame (`counted`), as
// 64-bit (low, high) word pairs: a low word that wraps carries into its high word.
// The counters start again at zero.
void rrc_io_flush(bool counted) {
    if (!COUNT_IO) return;
    for (int k = 0; k < RRC_IO_COUNTERS; ++k) {
        const uint add = rrc_io[k];
        rrc_io[k] = 0u;
        if (!counted || add == 0u) continue;
        const uint before = atomicAdd(u_stats.counters[RRC_IO_WORD(k)], add);
        if (before > 0xFFFFFFFFu - add) atomicAdd(u_stats.counters[RRC_IO_WORD(k) + 1], 1u);
    }
}

#endif
