// rrc-sweep: error against run time for rrc-sample's three applications
// (docs/measurements/PERFORMANCE.md, "Error against run time").  Runs the sweep, writes
// the CSVs, then fronts.py for the Pareto fronts, plots and verdicts.
#include "bias_output.h"
#include "clean_study.h"
#include "rectify_study.h"
#include "sweep_options.h"
#include "sweep_output.h"
#include "sweep_run.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#ifndef RRC_SWEEP_FRONTS_PY
#define RRC_SWEEP_FRONTS_PY "fronts.py"
#endif
#ifndef RRC_SWEEP_RECTIFY_PY
#define RRC_SWEEP_RECTIFY_PY "rectify_plot.py"
#endif
#ifndef RRC_SWEEP_BIAS_MAPS_PY
#define RRC_SWEEP_BIAS_MAPS_PY "bias_maps.py"
#endif
#ifndef RRC_SWEEP_PYTHON
#define RRC_SWEEP_PYTHON "python3"
#endif

namespace {

// The end every run shares: fail on validation messages, then the plotting script if any (matplotlib: Debian's python3-matplotlib).
int finish(const rrc_sweep::SweepOptions& o, uint64_t validation_messages, const char* script) {
    if (o.validation && validation_messages) {
        std::cerr << "rrc-sweep: " << validation_messages << " validation message(s)\n";
        return 1;
    }
    if (!o.plots || !script) return 0;
    const std::string py = std::string(RRC_SWEEP_PYTHON) + " '" + script + "' '" + o.out + "'";
    if (std::system(py.c_str()) == 0) return 0;
    std::cerr << "rrc-sweep: " << std::filesystem::path(script).filename().string() << " failed (" << py << ")\n";
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace rrc_sweep;
    SweepOptions o;
    const int code = rrc_host::parse_command_line("rrc-sweep", [&] { return parse_sweep_options(argc, argv); }, sweep_usage(), o);
    if (code >= 0) return code;
    std::string command = "rrc-sweep";
    for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
    try {
        if (o.study == "clean") {
            const CleanResult r = run_clean_study(o, &std::cout);
            write_clean_files(o, r, command);
            std::cout << "rrc-sweep --study clean: " << r.rows.size() << " rows in " << (int)r.seconds << " s; " << o.out << "/clean.md\n";
            return finish(o, r.validation_messages, nullptr);
        }
        if (o.study == "rectify") {
            const RectifyResult r = run_rectify_study(o, &std::cout);
            write_rectify_files(o, r, command);
            std::cout << "rrc-sweep --study rectify: " << r.rows.size() << " rows in " << (int)r.seconds << " s; " << o.out
                      << "/rectify.md\n";
            return finish(o, r.validation_messages, RRC_SWEEP_RECTIFY_PY);
        }
        const SweepResult r = run_sweep(o, &std::cout);
        write_sweep_files(o, r, command);
        if (o.bias_maps) write_region_tables(o, r);
        std::cout << "rrc-sweep: " << r.rrc.size() << " rrc rows, " << r.brute.size() << " brute-force rows in " << (int)r.seconds << " s; files in "
                  << o.out << "\n";
        const int fronts = finish(o, r.validation_messages, RRC_SWEEP_FRONTS_PY);
        if (fronts != 0 || !o.bias_maps) return fronts;
        return finish(o, r.validation_messages, RRC_SWEEP_BIAS_MAPS_PY);  // bias_regions_<app>.md and bias_<app>.png
    } catch (const std::exception& e) {
        std::cerr << "rrc-sweep: " << e.what() << "\n";
        return 1;
    }
}
