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

/** Throws CliError if any output path of the range names an input frame of
 *  the range or the camera file (same path after normalisation, or the same
 *  file through a link). */
void check_no_overwrite(const Options& options);

/** Runs the whole sequence: checks every frame's header, the camera file
 *  and the outputs before creating the rrc context, then reads, accumulates
 *  and writes frame by frame.  Progress and the summary go to `out`, errors
 *  (one line, "rrc-accumulate: ...") to `err`.  Returns kExitOk or
 *  kExitError. */
int run_accumulate(const Options& options, std::ostream& out, std::ostream& err);

/** main(): parse_arguments, --help, run_accumulate.  Without arguments the
 *  usage goes to `err` and the status is kExitUsage. */
int accumulate_main(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

} // namespace rrc_cli

#endif
