// The measured table of docs/measurements/STABILITY.md: each stability test adds rows
// (case, the bound it asserts, the value it measured) as it runs; with
// RRC_STABILITY_REPORT=<file> set, the executable replaces the text between
// its own pair of markers in that file when it finishes:
//   <!-- stability table RRC_STABILITY_SECTION: begin --> ... <!-- ...: end -->
// (RRC_STABILITY_SECTION is the executable's name, a compile definition), so
// the fast and the long test executables each own one table.
#pragma once

#include <string>

namespace rrc_stab {

// Records one measured row.  `bound` says what the test asserts; `measured`
// the value it found (already formatted).  A row with the same area and name
// is replaced (running summaries).
void report(const std::string& area, const std::string& name, const std::string& bound, const std::string& measured);

// printf into a std::string, for the measured and bound columns.
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace rrc_stab
