// The hit-test table of docs/measurements/ACCURACY.md: each case adds one row as it runs;
// with RRC_HIT_TEST_REPORT=<path to docs/measurements/ACCURACY.md> set, the executable
// replaces the text between
//   <!-- hit-test-recall:begin --> and <!-- hit-test-recall:end -->
// when it finishes (and appends the markers, under a short section, if the
// file lacks them).  Run the whole executable: the table holds the rows of
// the cases that ran.
#pragma once

#include <string>

namespace rrc_hit_report {

struct Row {
    std::string name;      // the case
    std::string scored;    // pixels scored (and the filter)
    std::string excluded;  // excluded pixels by reason
    std::string recall_fixed, recall_default, false_fixed, false_default;
    bool same_masks = false;  // the default run's masks equal FIXED's, bit for bit
};

void add(const Row& row);

// printf into a std::string.
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace rrc_hit_report
