// The sweep on the GPU: the targets of the checkpoint frames once, then every
// rrc run and the brute force, seed by seed, each row's error statistics
// (ensemble.h) and its GPU time by timestamps.
#pragma once

#include "bias_regions.h"
#include "ensemble.h"
#include "sweep_configs.h"
#include "sweep_options.h"

#include <ostream>
#include <string>
#include <vector>

namespace rrc_sweep {

struct RrcRow {
    RrcConfig config;
    int k = 1;
    uint32_t pattern = 0;
    double signal_ms = 0.0;  // the application's signal pass at k samples (median over frames and seeds)
    double rrc_ms = 0.0;        // its share of rrc: rrc_alone_ms less a third of what sharing a context saves (below)
    double rrc_alone_ms = 0.0;  // this channel's rrc dispatch alone (its own context; median)
    Metrics metrics;
    RegionParts regions;  // --bias-maps: bias² and variance by region
    bool has_regions = false;
};

struct BruteRow {
    BruteConfig config;
    double signal_ms = 0.0;
    Metrics metrics;
    RegionParts regions;
    bool has_regions = false;
};

struct SweepResult {
    uint32_t signals = 0;
    std::string device;
    std::vector<RrcRow> rrc;
    std::vector<BruteRow> brute;
    std::vector<double> hit_ratio;  // per frame of the first run's first seed
    // The three applications' default channels alone and together in one context (median ms):
    // sharing saves alone_sum - together, a third of which each application's share drops.
    double rrc_together_ms = 0.0, rrc_alone_sum_ms = 0.0;
    std::string clock;               // which clock the times are read from
    double stamps_over_wall = 0.0;   // median per frame: timestamps' sum over the wall clock's, signal passes and rrc
    double seconds = 0.0;
    uint64_t validation_messages = 0;
};

/** Runs the whole sweep.  progress: a line per run and seed (nullptr: none).  Throws std::runtime_error. */
SweepResult run_sweep(const SweepOptions& options, std::ostream* progress);

}  // namespace rrc_sweep
