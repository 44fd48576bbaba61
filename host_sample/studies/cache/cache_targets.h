// rrc-cache's speed-up against shader cost and its targets (README.md,
// "Targets"): the same TILED n = 4 cache with the shader at each octave count
// (perlin.glsl's kOctaves), the break-even shader where the speed-up crosses 1
// (linear between measured points), and the verdict of each target:
// classify + resolve <= 0.40 of the full frame (640x360, 8 octaves), the
// break-even shader at TILED n = 4 <= 16 octaves, speed-up >= 0.85 x the
// Amdahl bound in every cached run.  Pure functions of the figures, tested on
// made-up ones (cache_test.cpp).
#pragma once

#include "cache_report.h"

#include <string>
#include <vector>

namespace rrc_cache {

// The paper's speed-up at a refresh period of 4 frames (Nehab et al. 2007, the shading-cache results).
constexpr double kPaperSpeedupLow = 1.7, kPaperSpeedupHigh = 1.9;
// The targets.
constexpr double kTargetCacheShare = 0.40, kTargetBreakEvenOctaves = 16, kTargetOfBound = 0.85;
constexpr uint32_t kTargetWidth = 640, kTargetHeight = 360, kCostPeriod = 4;

/** One octave count: the TILED n = 4 run (no lifetime, one view, one sub-frame) at that cost. */
struct CostPoint {
    uint32_t octaves = 0;
    std::string run;
    double shade_ms = 0;  // the full shading pass per frame (the paired baseline's, same frames)
    double full_ms = 0, speedup = 0, bound = 0, of_bound = 0, c = 0, shaded_fraction = 0, rmse = 0;
};

/** The cost curve, by octave count ascending; the first such run at each count. */
std::vector<CostPoint> cost_curve(const std::vector<Figures>& f);

struct BreakEven {
    enum Kind {
        kUnmeasured,  // no point
        kAtOrBelow,   // the cheapest shader measured already breaks even: at or below it
        kBetween,     // interpolated between two measured points
        kNotReached,  // no measured shader breaks even
    } kind = kUnmeasured;
    double octaves = 0, shade_ms = 0;  // kAtOrBelow: the cheapest point's; kBetween: interpolated
};

/** Where speed-up = 1: the first measured point at or above 1, interpolated linearly (in octaves and
 *  in shading ms alike) from the point before it. */
BreakEven break_even(const std::vector<CostPoint>& curve);

struct Verdict {
    std::string target;    // what is asked
    std::string measured;  // what was measured
    bool met = false;
    std::string verdict;   // "met", "missed by ...", "not measured ..."
};

/** The three targets' verdicts from the runs' figures. */
std::vector<Verdict> verdicts(const std::vector<Figures>& f, const Settings& s);

}  // namespace rrc_cache
