// rrc-cache's figures from the runs: medians of the per-frame times (frames
// after the first two: the first misses everywhere, the second warms up), the
// Amdahl bound 1/((1 - p) + p*f + c) from the baseline's shading share p, the
// run's shaded fraction f and its classify + resolve cost c, and the
// measured speed-up against it; written as report.md and runs.csv.  The
// baseline of a cached run is paired: the same frames' G-buffers shaded
// everywhere, each timed right after the cached frame (the error target).
#pragma once

#include "cache_run.h"

#include <string>
#include <vector>

namespace rrc_cache {

struct Figures {
    std::string name;
    CacheConfig config;  // the run's (policy, n, eyes, sub-frames, octaves)
    double raster_ms = 0, shade_ms = 0, rrc_ms = 0, total_ms = 0;                    // medians
    double shaded_fraction = 0, rmse = 0, hit_fraction = 0, refreshed_fraction = 0;  // means
    // The paired baseline: the same frames shaded everywhere, timed beside each cached frame (medians).
    double full_shade_ms = 0, full_ms = 0;
    double p = 0, c = 0, bound = 0, speedup = 0, of_bound = 0;  // against the paired baseline
    double speedup_separate = 0;  // against the separate run shading every pixel (same eyes, sub-frames): load drifts between runs
    bool list_matched = true;
};

/** Per run: the paired baseline, and the separate run shading every pixel with the same eyes and sub-frames. */
std::vector<Figures> figures(const std::vector<RunResult>& runs);

// The time model (README.md, the speed-up and the Amdahl bound): pure functions of the medians,
// tested on made-up timings (cache_test.cpp, RrcCacheReport.*), since on a loaded machine a measured
// time may be 0 and a bound computed from it 0 or infinite.

/** 1/((1 - p) + p*f + c); infinite where that is 0 (p = 1, f = 0, c = 0: nothing left to do). */
double amdahl_bound(double p, double f, double c);

/** From f's medians (shade_ms, rrc_ms, total_ms, full_shade_ms, full_ms) and its shaded fraction:
 *  p = full_shade_ms / full_ms, c = rrc_ms / full_ms (0 without the cache), the bound, speed-up =
 *  full_ms / total_ms and speed-up / bound.  A zero full_ms or total_ms (nothing measured) leaves
 *  them all 0. */
void apply_time_model(Figures& f, bool cache);

/** baseline_ms / frame_ms; 0 when either is not positive (not measured). */
double speedup_against(double baseline_ms, double frame_ms);

/** runs.csv: one row a run (README.md, Output). */
void write_csv(const std::string& path, const std::vector<Figures>& f);
/** speedup_vs_cost.csv: one row an octave count, TILED n = 4 against the same frames shaded everywhere. */
void write_cost_csv(const std::string& path, const std::vector<Figures>& f);
void write_report(const std::string& path, const std::vector<Figures>& f, const std::string& command, const std::string& device,
                  const Settings& settings);

}  // namespace rrc_cache
