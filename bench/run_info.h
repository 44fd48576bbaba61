// Where and when a run happened, for the reports: the commit of the source
// tree the bench was built from (the kernel changes under it), the date,
// the CPU.
#pragma once

#include <string>

namespace rrc_bench {

/** `git describe --always --dirty` of the source tree, "unknown" without git. */
std::string source_commit();
/** UTC, ISO 8601. */
std::string utc_now();
/** "model name" of /proc/cpuinfo and the number of CPUs online. */
std::string cpu_description();
/** The 1-minute load average (/proc/loadavg): how shared the machine was. */
double load_average();

}  // namespace rrc_bench
