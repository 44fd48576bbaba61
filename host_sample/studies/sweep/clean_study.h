// What rrc adds to a clean input (rrc-sweep --study clean; README.md, "Clean
// input"): the test bed's signals replaced by their noise-free targets, each
// application accumulated with rrc-sample's preset (with and without its
// base), and the output scored against the frame's own input by region
// (clean_regions.h).
#pragma once

#include "sweep_configs.h"
#include "sweep_options.h"

#include <clean_regions.h>

#include <ostream>
#include <string>
#include <vector>

namespace rrc_sweep {

struct CleanRow {
    App app;
    std::string preset;  // "preset" or "preset without its base"
    rrc_sample::ChannelSettings channel;
    rrc_host::CleanSums sums;  // over the scored frames
};

struct CleanResult {
    std::string device;
    std::vector<CleanRow> rows;
    int scored_frames = 0;
    double seconds = 0.0;
    uint64_t validation_messages = 0;
};

/** Runs the study (o.study == "clean"): frames 0 .. o.frames - 1 from a reset, scored at o.checkpoints().
 *  Throws std::runtime_error. */
CleanResult run_clean_study(const SweepOptions& o, std::ostream* progress);

/** clean.csv (a row per preset row and region) and clean.md (the table, the settings) in o.out. */
void write_clean_files(const SweepOptions& o, const CleanResult& r, const std::string& command_line);

}  // namespace rrc_sweep
