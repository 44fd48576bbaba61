// The sweep's files: sweep_<app>.csv (one row per configuration, the columns
// fronts.py reads), hit_ratio.csv, and sweep.md (settings, device, timings).
#pragma once

#include "sweep_options.h"
#include "sweep_run.h"

#include <string>

namespace rrc_sweep {

/** Writes every file into options.out; throws std::runtime_error if one cannot be written. */
void write_sweep_files(const SweepOptions& options, const SweepResult& result, const std::string& command_line);

}  // namespace rrc_sweep
