// The run's summary: summary.md (configuration, per-frame table, errors
// against the reference), summary.csv (one row per frame), errors.csv (one
// row per checkpoint and signal), and the table printed at the end.
#pragma once

#include "sample_run.h"

#include <ostream>
#include <string>

namespace rrc_sample {

void write_summary_files(const RunResult& run, const std::string& out_dir);
void print_summary(const RunResult& run, std::ostream& os);
/** One progress line for a frame. */
std::string progress_line(const FrameRecord& f, int frames);

}  // namespace rrc_sample
