// rrc-accumulate --clean-report: the accumulated output against each frame's
// own input, by region (clean_regions.h; docs/measurements/OFFLINE.md, "What rrc adds to a
// clean input").  Fed frame by frame by run_accumulate.
#ifndef RRC_ACCUMULATE_CLEAN_REPORT_H
#define RRC_ACCUMULATE_CLEAN_REPORT_H

#include "options.h"
#include "sequence.h"

#include <clean_regions.h>

#include <ostream>
#include <string>
#include <vector>

namespace rrc_cli {

class CleanReport {
public:
    /** fill_ages: each signal's channel fill_age as the context has it (0: no fill). */
    CleanReport(const Options& options, const SequenceLayout& layout, std::vector<uint32_t> fill_ages);

    /** One frame's regions and errors, every signal; `data` the frame's input, `result` rrc's outputs. */
    void add_frame(int64_t frame, const FrameData& data, const FrameResult& result);

    /** Writes the file (markdown: the summary tables; CSV: a row per frame, signal and region) and
     *  prints a summary line per signal to `out`. */
    void finish(std::ostream& out) const;

    /** The summed errors of signal s over the summary's frames (>= --from). */
    const rrc_host::CleanSums& summary(size_t s) const { return summary_[s]; }

private:
    const Options& options_;
    const SequenceLayout& layout_;
    std::vector<uint32_t> fill_ages_;
    std::vector<rrc_host::CleanSums> summary_;
    int64_t frames_ = 0;
    std::string csv_;
};

}  // namespace rrc_cli

#endif
