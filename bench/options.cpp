#include "options.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#ifndef RRC_BENCH_PLOT_SCRIPT
#define RRC_BENCH_PLOT_SCRIPT "bench/plot.py"
#endif

namespace rrc_bench {
namespace {

[[noreturn]] void usage(int code) {
    std::fprintf(code ? stderr : stdout,
                 "usage: rrc-bench [--full] [--list] [--config NAME[,NAME...]] [--size WxH] [--reps N] [--warmup N]\n"
                 "                 [--nocache-share S] [--device TEXT] [--validation] [--check-roof] [--out DIR] [--no-plot]\n"
                 "                 [--plot-script PATH]\n"
                 "Times rrc's kernel (interop path) against its roof, a copy kernel moving the bytes the API implies,\n"
                 "and the standalone round trip against kernel + memcpy.  Default: a short sweep (under 2 minutes on\n"
                 "2 cores); --full: every factor around the base (1920x1080, one fp16 channel, PREV_CLIP).\n"
                 "--config takes names printed by `rrc-bench --list`.  Results: DIR/bench.csv, bench.json, report.md, bench.png.\n"
                 "--nocache-share S: the share of pixels (0 to 1) the nocache mask marks in the young* rows, the fill's\n"
                 "workload at a stated young fraction (default 0.08: about 12 %% of the pixels young at 1080p); every row\n"
                 "reports the young fraction it measured (surface pixels of age < 8 over all pixels).\n");
    std::exit(code);
}

}  // namespace

Options parse_options(int argc, char** argv) {
    Options o;
    o.plot_script = RRC_BENCH_PLOT_SCRIPT;
    for (int i = 0; i < argc; ++i) o.command_line += std::string(i ? " " : "") + argv[i];
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "rrc-bench: %s needs a value\n", a.c_str());
                usage(2);
            }
            return argv[++i];
        };
        if (a == "--help" || a == "-h") usage(0);
        else if (a == "--full") o.full = true;
        else if (a == "--list") o.configs = {"list"};
        else if (a == "--config") {
            const std::string v = value();
            size_t start = 0;
            while (start <= v.size()) {
                const size_t comma = v.find(',', start);
                const std::string name = v.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
                if (!name.empty()) o.configs.push_back(name);
                if (comma == std::string::npos) break;
                start = comma + 1;
            }
        } else if (a == "--size") {
            const std::string v = value();
            if (std::sscanf(v.c_str(), "%ux%u", &o.width, &o.height) != 2 || !o.width || !o.height) {
                std::fprintf(stderr, "rrc-bench: --size wants WxH, got %s\n", v.c_str());
                usage(2);
            }
        } else if (a == "--reps") o.reps = std::atoi(value().c_str());
        else if (a == "--warmup") o.warmup = std::atoi(value().c_str());
        else if (a == "--nocache-share") {
            const std::string v = value();
            char* end = nullptr;
            o.nocache_share = std::strtof(v.c_str(), &end);
            if (end == v.c_str() || *end || !(o.nocache_share >= 0.0f && o.nocache_share <= 1.0f)) {
                std::fprintf(stderr, "rrc-bench: --nocache-share wants a share in [0, 1], got %s\n", v.c_str());
                usage(2);
            }
        } else if (a == "--device") o.device = value();
        else if (a == "--validation") o.validation = true;
        else if (a == "--check-roof") o.check_roof = true;
        else if (a == "--out") o.out = value();
        else if (a == "--no-plot") o.plot = false;
        else if (a == "--plot-script") o.plot_script = value();
        else {
            std::fprintf(stderr, "rrc-bench: unknown option %s\n", a.c_str());
            usage(2);
        }
    }
    if (o.reps < 0 || o.warmup < 0) usage(2);
    return o;
}

}  // namespace rrc_bench
