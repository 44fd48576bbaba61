// rrc-sample: a headless Vulkan renderer that drives rrc through its interop
// path.  README.md (this folder) describes the scene, the signals, the
// outputs and what the numbers mean.
#include "options.h"
#include "sample_run.h"
#include "summary.h"

#include <iostream>

int main(int argc, char** argv) {
    using namespace rrc_sample;
    Options options;
    const int code = rrc_host::parse_command_line("rrc-sample", [&] { return parse_options(argc, argv); }, usage(), options, true);
    if (code >= 0) return code;
    try {
        RunResult run = run_sample(options, &std::cout);
        print_summary(run, std::cout);
        if (options.validation && run.validation_messages) {
            std::cerr << "rrc-sample: " << run.validation_messages << " validation message(s); the first:\n";
            for (const std::string& m : run.messages) std::cerr << "  " << m << "\n";
            return 1;
        }
    } catch (const std::exception& e) {
        std::cerr << "rrc-sample: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
