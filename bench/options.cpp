#include "options.h"

#include "options_parser.h"

#include <cstdio>
#include <cstdlib>

#ifndef RRC_BENCH_PLOT_SCRIPT
#define RRC_BENCH_PLOT_SCRIPT "bench/plot.py"
#endif

namespace rrc_bench {
namespace {

[[noreturn]] void usage(int code) {
    std::fprintf(code ? stderr : stdout,
                 "usage: rrc-bench [--full] [--list] [--config NAME[,NAME...]] [--size WxH] [--reps N] [--warmup N]\n"
                 "                 [--nocache-share S] [--device TEXT] [--validation] [--check-roof] [--out DIR] [--no-plot]\n"
                 "                 [--plot-script PATH] [--check-options]\n"
                 "Times rrc's kernel (interop path) against its roof, a copy kernel moving the bytes the API implies,\n"
                 "and the standalone round trip against kernel + memcpy.  Default: a short sweep (under 2 minutes on\n"
                 "2 cores); --full: every factor around the base (1920x1080, one fp16 channel, PREV_CLIP).\n"
                 "--config takes names printed by `rrc-bench --list`.  Results: DIR/bench.csv, bench.json, report.md, bench.png.\n"
                 "--nocache-share S: the share of pixels (0 to 1) the nocache mask marks in the young* rows, the fill's\n"
                 "workload at a stated young fraction (default 0.08: about 12 %% of the pixels young at 1080p); every row\n"
                 "reports the young fraction it measured (surface pixels of age < 8 over all pixels).\n"
                 "--check-options: check the options as a run would (the --config names included), print\n"
                 "\"rrc-bench: options ok\" and exit.\n");
    std::exit(code);
}

}  // namespace

Options parse_options(int argc, char** argv) {
    Options o;
    o.plot_script = RRC_BENCH_PLOT_SCRIPT;
    for (int i = 0; i < argc; ++i) o.command_line += std::string(i ? " " : "") + argv[i];
    bool help = false;
    try {
        rrc_host::ArgCursor c(argc, argv);
        while (c.next()) {
            if (c.flag("--full")) o.full = true;
            else if (c.flag("--list")) o.configs = {"list"};
            else if (c.option("--config")) o.configs = c.names();
            else if (c.option("--size")) c.size(o.width, o.height, 1, 16384);
            else if (c.option("--reps")) o.reps = (int)c.integer(0, 100000);
            else if (c.option("--warmup")) o.warmup = (int)c.integer(0, 100000);
            else if (c.option("--nocache-share")) o.nocache_share = c.number(0.0f, 1.0f);
            else if (c.option("--device")) o.device = c.value();
            else if (c.flag("--validation")) o.validation = true;
            else if (c.flag("--check-roof")) o.check_roof = true;
            else if (c.option("--out")) o.out = c.value();
            else if (c.flag("--no-plot")) o.plot = false;
            else if (c.option("--plot-script")) o.plot_script = c.value();
            else c.unknown();
        }
        o.check_options = c.check_only();
        help = c.help();
    } catch (const rrc_host::OptionError& e) {
        std::fprintf(stderr, "rrc-bench: %s\n", e.what());
        usage(2);
    }
    if (help) usage(0);
    return o;
}

}  // namespace rrc_bench
