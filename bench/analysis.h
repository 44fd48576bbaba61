// The checks docs/measurements/PERFORMANCE.md sets: linearity in the pixel count and the
// targets, each reported as met, missed (by how much) or not measured (its
// configurations were not in the run).
#pragma once

#include "result.h"

#include <string>
#include <vector>

namespace rrc_bench {

struct Linearity {
    bool measured = false;
    // Fitted round by round (every row ran once per round of repetitions), medians over the rounds.
    double ms_per_mpixel = 0;                  // kernel ms per megapixel, least squares through 0 over 720p..4K
    double intercept_ms = 0, slope_ms = 0;     // ms = intercept + slope * MP over every resolution row (the plot's line)
    std::vector<std::pair<std::string, double>> deviation;  // 720p..4K rows: ms / (k * MP) - 1
    double max_abs_deviation = 0;
    bool small_measured = false;
    double small_share = 0;                    // 256x160: ms / (k * MP)
};

struct Target {
    std::string name, goal, measured;
    std::string status;  // "met", "missed", "not measured"
    std::string margin;  // how far inside or outside the goal
};

Linearity analyze_linearity(const std::vector<Row>& rows);
std::vector<Target> evaluate_targets(const std::vector<Row>& rows, const Linearity& lin);

}  // namespace rrc_bench
