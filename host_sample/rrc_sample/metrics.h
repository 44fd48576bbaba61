// Per-frame numbers: hit ratio from rrc's mask, RMSE/PSNR of a signal
// against the brute-force reference.
#pragma once

#include "renderer.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rrc_sample {

struct HitStats {
    uint64_t hits = 0, misses = 0, refreshed = 0, background = 0;
    double ratio() const { return hits + misses ? (double)hits / (double)(hits + misses) : 0.0; }
};
HitStats hit_stats(const std::vector<uint8_t>& mask);

struct ErrorStats {
    double rmse = 0.0, psnr = 0.0;  // PSNR with peak 1 (signals live in [0, 1]; env is HDR, clipped at no value)
    uint64_t pixels = 0;
};

/** Over pixels with valid[i] != 0; the first `compare` of `components` channels. */
ErrorStats error_against(const std::vector<float>& value, const std::vector<float>& reference, int components, int compare,
                         const std::vector<uint8_t>& valid);

/** Errors of one signal on a checkpoint frame. */
struct SignalErrors {
    std::string signal;
    ErrorStats raw, accumulated;
    ErrorStats brute_force;                 // 4x the per-frame samples, one frame
    ErrorStats shown, fallback;             // soft only: displayed (accumulated + PCSS fallback), PCSS alone
    ErrorStats raw_hits, accumulated_hits;  // over cache hits only
};

/** Hits whose history comes from another surface.  For each hit on a static
 *  surface (not the moving torus), a bilinear tap around the pixel's true
 *  previous position (the G-buffer's previous clip position) is "foreign" if,
 *  in the previous frame, it held the background, the torus, or a point more
 *  than 2 pixel footprints (+5 mm) from the pixel's own point (the footprint:
 *  the pixel's angular size times its distance over |cos| of the view angle,
 *  at least 0.02).  A false hit takes at least 1/4 of its history from
 *  foreign taps; a strict false hit any tap weight above 1e-3 (as
 *  docs/ACCURACY.md counts them).  Contact lines pass (their taps are close). */
struct FalseHitStats {
    uint64_t checked = 0, false_hits = 0, strict = 0;
    double rate() const { return checked ? (double)false_hits / (double)checked : 0.0; }
};
FalseHitStats count_false_hits(const FrameOutput& previous, const FrameOutput& current, uint32_t width, uint32_t height);

/** The errors of every enabled signal of a checkpoint frame (empty otherwise). */
std::vector<SignalErrors> frame_errors(const FrameOutput& frame);

}  // namespace rrc_sample
