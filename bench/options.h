// rrc-bench's command line.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rrc_bench {

struct Options {
    bool full = false;                  // --full: every configuration of the sweep
    std::vector<std::string> configs;   // --config a,b: only these (overrides --full)
    uint32_t width = 0, height = 0;     // --size WxH: every configuration at this size
    int reps = 0;                       // --reps N: timed repetitions (0: 9 short run, 15 full)
    int warmup = 3;                     // --warmup N: untimed frames first
    float nocache_share = -1;           // --nocache-share S: the young rows' nocache share (< 0: kYoungNocacheShare)
    std::string device;                 // --device TEXT: substring of the device name
    bool validation = false;            // --validation: Khronos validation + sync validation, fail on any message
    bool check_roof = false;            // --check-roof: read the roof's outputs back, fail unless exact copies
    std::string out = "out/bench";      // --out DIR
    bool plot = true;                   // --no-plot: skip bench/plot.py
    std::string plot_script;            // --plot-script PATH (default: the source tree's bench/plot.py)
    std::string command_line;           // as given, for the reports
    bool check_options = false;         // --check-options: validate (the --config names too), print "options ok", exit
};

/** Parses argv (options_parser.h); prints usage and exits on --help or an error. */
Options parse_options(int argc, char** argv);

}  // namespace rrc_bench
