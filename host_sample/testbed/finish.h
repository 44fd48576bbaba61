// The finishing steps' measurements (README.md, "Finishing steps"; the
// figures in docs/measurements/finish/): the errors of young (newly disoccluded)
// soft-shadow pixels by age, the error of every display on each checkpoint (a
// convergence curve), and raw float dumps of the displays for figures.  The
// fill's figures come from rrc's own fill (--soft-fill), whose output is the
// accumulated display; its double-precision model is the test suite's
// (tests/reference/finish.h).
#pragma once

#include "metrics.h"
#include "options.h"
#include "renderer.h"

#include <array>
#include <string>
#include <vector>

namespace rrc_sample {

/** The finishing steps' extra errors of a checkpoint (empty otherwise), beside metrics.h's. */
struct FinishErrors {
    ErrorStats pcf_display;         // pcf's remapped display (--pcf-smoothstep, --pcf-threshold) against the fixed target
    ErrorStats pcf_vs_weighted;     // with confidence: the accumulated pcf against the confidence-weighted disk mean
    ErrorStats weighted_vs_target;  // with confidence: that weighted mean against the fixed target (the disk mean)
};
FinishErrors finish_errors(const FrameOutput& frame);

/** Accumulates, over a run, the soft channel's error by pixel age and per checkpoint. */
class FinishReport {
public:
    enum Display { kRaw, kAccumulated, kShown, kPcss, kDisplayCount };
    static const char* name(Display d);

    FinishReport(const Options& options, uint32_t signals);
    /** Every frame, in order.  verdict: the oracle's per-pixel Verdict bits (oracle.h), which
     *  tell a true disocclusion (a miss on a point not visible in the previous frame) from a
     *  miss the depth test made on a visible point; each track keeps its start's kind, carried
     *  like the age (nearest at the previous position).  Errors only on checkpoints with a soft reference. */
    void add(const FrameOutput& frame, const std::vector<uint8_t>& verdict);
    /** young.csv, curve.csv (and the dumps were written by add). */
    void write(const std::string& out_dir) const;
    /** A short table for the progress stream. */
    std::string table() const;

private:
    Options o_;
    bool enabled_ = false;
    struct Sum {
        double sq = 0.0;
        uint64_t n = 0;
        double rmse() const;
    };
    // [0] every young track, [1] tracks started by a true disocclusion (the oracle)
    std::vector<std::array<Sum, kDisplayCount>> by_age_[2];  // index a - 1
    std::array<Sum, kDisplayCount> young_[2];                // ages 1..N pooled
    std::vector<uint8_t> kind_;                              // per pixel: 0 none, 1 disocclusion, 2 other miss
    struct Row {
        int frame;
        std::array<double, kDisplayCount> rmse;
    };
    std::vector<Row> curve_;
};

}  // namespace rrc_sample
