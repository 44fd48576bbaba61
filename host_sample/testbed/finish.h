// Issue 13's measurements of the finishing steps on the soft-shadow channel:
// a CPU model of rrc's spatial fill (docs/CONVENTIONS.md, "The spatial fill"),
// the errors of young (newly disoccluded) pixels by age, the error of every
// display on each checkpoint (a convergence curve), and raw float dumps of the
// displays for figures (docs/finish/).
#pragma once

#include "frame_state.h"
#include "metrics.h"
#include "options.h"
#include "renderer.h"

#include <array>
#include <string>
#include <vector>

namespace rrc_sample {

struct FillParams {
    uint32_t age = 8;         // T
    uint32_t radius = 2;      // r
    float tolerance = RRC_DEFAULT_FILL_DEPTH_TOLERANCE;  // tau
    float prior = 0.0f;       // P, the fallback's weight in samples (0: none)
};

/** The fill of docs/CONVENTIONS.md on the CPU, for a one-component channel:
 *  values = the channel's history after the frame (rrc's output without a fill),
 *  ages = the pixel ages (the host's map), the depth proxy from the G-buffer
 *  position through view_proj (reversed z: delta = 1/z), fallback = the PCSS
 *  estimate (used iff prior > 0).  Returns the displayed value of every pixel. */
std::vector<float> fill_model(const FrameOutput& frame, const glm::dmat4& view_proj, const std::vector<float>& values,
                              const std::vector<float>& fallback, const FillParams& params);

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
    enum Display { kRaw, kAccumulated, kShown, kPcss, kFillPrior, kFillNone, kDisplayCount };
    static const char* name(Display d);

    FinishReport(const Options& options, uint32_t signals);
    /** Every frame, in order.  verdict: the oracle's per-pixel Verdict bits (oracle.h), which
     *  tell a true disocclusion (a miss on a point not visible in the previous frame) from a
     *  miss the depth test made on a visible point; each track keeps its start's kind, carried
     *  like the age (nearest at the previous position).  Errors only on checkpoints with a soft reference. */
    void add(const FrameOutput& frame, const FrameState& state, const std::vector<uint8_t>& verdict);
    /** young.csv, curve.csv (and the dumps were written by add). */
    void write(const std::string& out_dir) const;
    /** A short table for the progress stream. */
    std::string table() const;
    bool model() const { return model_; }

private:
    Options o_;
    bool enabled_ = false, model_ = false;
    FillParams prior_, none_;
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
