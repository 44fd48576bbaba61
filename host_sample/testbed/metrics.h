// Per-frame numbers: hit ratio from rrc's mask, RMSE/PSNR of a signal
// against the brute-force reference.  Recall and false hits: oracle.h.
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
    ErrorStats shown, fallback;             // soft: displayed (accumulated + PCSS fallback), PCSS alone; pcf, env: -, the residual's base alone
    ErrorStats raw_hits, accumulated_hits;  // over cache hits only
};

/** printf-formats one number (the tables' and CSVs' cells). */
std::string fmt(const char* format, double value);

/** The errors of every enabled signal of a checkpoint frame (empty otherwise). */
std::vector<SignalErrors> frame_errors(const FrameOutput& frame);

}  // namespace rrc_sample
