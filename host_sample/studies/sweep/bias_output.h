// The bias maps' files (README.md, "Bias maps"): one EXR a row with its
// signed bias map at every checkpoint, one EXR an application with its
// regions, target and rrc's age, and bias_regions_<app>.csv with every
// row's bias² and variance by region.  bias_maps.py draws and tabulates them.
#pragma once

#include "bias_regions.h"
#include "sweep_options.h"
#include "sweep_run.h"

#include <string>
#include <vector>

namespace rrc_sweep {

/** A row's name in the files: pcf_rrc_k4_age-aware_l0.8_bilinear, soft_rrc_k4_running-mean_bilinear_cap64, pcf_brute_k16. */
std::string row_label(const RrcRow& row);
std::string row_label(const BruteRow& row);

/** out/bias_maps/<label>.exr: a float channel "bias.cp<t>" per checkpoint t (NaN: not scored). */
void write_bias_map(const SweepOptions& o, const std::string& label, const std::vector<std::vector<float>>& per_checkpoint);

/** out/bias_maps/<app>_regions.exr: per checkpoint t, "region.cp<t>" (Region, 255 unscored),
 *  "age.cp<t>" (rrc's age), all float channels, and "target.cp<t>" (float: the target, mean over its components). */
void write_region_images(const SweepOptions& o, const char* app, const std::vector<std::vector<uint8_t>>& regions,
                         const std::vector<std::vector<uint16_t>>& ages, const std::vector<std::vector<float>>& targets);

/** out/bias_regions_<app>.csv for every application of the result: a line per row and region. */
void write_region_tables(const SweepOptions& o, const SweepResult& r);

}  // namespace rrc_sweep
