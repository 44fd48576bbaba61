// rrc-accumulate: the tool's core (everything but main()).
#ifndef RRC_ACCUMULATE_ACCUMULATE_H
#define RRC_ACCUMULATE_ACCUMULATE_H

#include "options.h"

#include <ostream>

namespace rrc_cli {

/** Exit statuses. */
constexpr int kExitOk = 0;
constexpr int kExitError = 1; /* a file, channel, library or validation error */
constexpr int kExitUsage = 2; /* a bad command line */

/** Throws CliError if any output path of the range (EXR frames, --coherence
 *  PNGs, the metrics CSV) names an input (a frame of the range, a
 *  --reference frame, the camera file: same path after normalisation, or
 *  the same file through a link), or two outputs name the same file. */
void check_no_overwrite(const Options& options);

/** Runs the whole sequence: checks every frame's header and block table
 *  (and the --reference frames'), the camera file and the outputs before
 *  creating the rrc context, then reads, accumulates and writes frame by
 *  frame.  Progress and the summary go to `out` (Progress::Auto means lines
 *  here; accumulate_main resolves it), errors (one line, "rrc-accumulate:
 *  ...") to `err`.  Returns kExitOk or kExitError. */
int run_accumulate(const Options& options, std::ostream& out, std::ostream& err);

/** main(): parse_arguments, --help, run_accumulate.  Without arguments the
 *  usage goes to `err` and the status is kExitUsage.  `out_is_terminal`
 *  turns --progress auto into a progress bar. */
int accumulate_main(int argc, const char* const* argv, std::ostream& out, std::ostream& err, bool out_is_terminal = false);

}  // namespace rrc_cli

#endif
