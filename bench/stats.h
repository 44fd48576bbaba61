// Summaries of repeated timings: the median (robust on a shared, noisy
// machine), the extremes, and the interquartile range.
#pragma once

#include <chrono>
#include <vector>

namespace rrc_bench {

struct Summary {
    double median = 0, min = 0, max = 0, q1 = 0, q3 = 0;
    size_t count = 0;
};

Summary summarize(std::vector<double> values);

/** Milliseconds since an arbitrary epoch (steady clock). */
inline double now_ms() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace rrc_bench
