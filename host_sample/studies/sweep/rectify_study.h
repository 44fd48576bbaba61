// The rectification study (rrc-sweep --study rectify; README.md,
// "Rectification study"): with the light moving at a fixed speed, how far
// rrc's accumulated signal lags behind the moving light's target on the
// pixels whose target changed, and, with the light fixed, the ensemble
// variance; each row with history rectification off and on
// (docs/CONVENTIONS.md, "Rectification"), with the lag detector on
// (docs/CONVENTIONS.md, "The lag detector"), and env with the view lobe fed
// the lighting's turn (docs/CONVENTIONS.md, "The view-dependent history").
#pragma once

#include "ensemble.h"
#include "sweep_configs.h"
#include "sweep_options.h"

#include <ostream>
#include <string>
#include <vector>

namespace rrc_sweep {

struct RectifyRow {
    App app;
    float lambda = 0.0f;
    uint32_t rectify = 0;
    float gamma = 0.0f;  // 0 when rectify is off
    uint32_t antilag = 0;
    float antilag_gamma = 0.0f, antilag_threshold = 0.0f;  // 0 when antilag is off
    rrc_sample::ChannelSettings channel;                    // every setting of the row's channel
    std::string preset;  // "" a study row; else which rrc-sample preset row (rectify_study.cpp, study_configs)
    bool lighting_turn = false;  // a view lobe whose frames carry the environment map's turn (rrc_frame_desc.lighting_turn)
    int base = -1;       // the index in rows of the same row without its cure; -1 for a row without one
    Metrics lag;         // light moving: against its target, on the changed pixels only (rmse = the lag error)
    Metrics still;       // light fixed: every scored pixel (variance = the static variance)
};

struct RectifyResult {
    std::string device;
    int k = 4;
    float light_speed = 0.0f;
    std::vector<RectifyRow> rows;
    // Per application (pcf, env, soft order of apps_of): the changed pixels' share of the scored
    // pixels, averaged over checkpoints, the threshold that defined them, and the mean |change|.
    std::vector<App> apps;
    std::vector<double> changed_fraction, change_threshold, mean_change;
    std::vector<size_t> changed_pixels;  // summed over checkpoints
    double seconds = 0.0;
    uint64_t validation_messages = 0;
};

/** Runs the study (o.study == "rectify"; o.light_speed != 0).  Throws std::runtime_error. */
RectifyResult run_rectify_study(const SweepOptions& o, std::ostream* progress);

/** rectify.csv and rectify.md (the table, the verdicts, the settings) in o.out. */
void write_rectify_files(const SweepOptions& o, const RectifyResult& r, const std::string& command_line);

/** The lag-error threshold: a pixel changed when a component of its target moved by more than this
 *  between the frame and the one before: pcf and soft `tau` (--change-threshold); env 3 standard
 *  deviations of the difference of two target estimates whose noise is `noise` per value, at least 0.01. */
double change_threshold(uint32_t signal, double tau, double noise);

}  // namespace rrc_sweep
