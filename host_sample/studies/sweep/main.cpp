// rrc-sweep: error against run time for rrc-sample's three applications
// (docs/PERFORMANCE.md, "Error against run time").  Runs the sweep, writes
// the CSVs, then fronts.py for the Pareto fronts, plots and verdicts.
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
#ifndef RRC_SWEEP_PYTHON
#define RRC_SWEEP_PYTHON "python3"
#endif

int main(int argc, char** argv) {
    using namespace rrc_sweep;
    SweepOptions o;
    try {
        o = parse_sweep_options(argc, argv);
    } catch (const OptionError& e) {
        std::cerr << "rrc-sweep: " << e.what() << "\n";
        return 2;
    }
    if (o.help) {
        std::cout << sweep_usage();
        return 0;
    }
    std::string command = "rrc-sweep";
    for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
    if (o.study == "rectify") {
        try {
            const RectifyResult r = run_rectify_study(o, &std::cout);
            write_rectify_files(o, r, command);
            std::cout << "rrc-sweep --study rectify: " << r.rows.size() << " rows in " << (int)r.seconds << " s; " << o.out
                      << "/rectify.md\n";
            if (o.validation && r.validation_messages) {
                std::cerr << "rrc-sweep: " << r.validation_messages << " validation message(s)\n";
                return 1;
            }
            if (o.plots) {
                const std::string py = std::string(RRC_SWEEP_PYTHON) + " '" + RRC_SWEEP_RECTIFY_PY + "' '" + o.out + "'";
                if (std::system(py.c_str()) != 0) {
                    std::cerr << "rrc-sweep: rectify_plot.py failed (" << py << ")\n";
                    return 1;
                }
            }
        } catch (const std::exception& e) {
            std::cerr << "rrc-sweep: " << e.what() << "\n";
            return 1;
        }
        return 0;
    }
    try {
        const SweepResult r = run_sweep(o, &std::cout);
        write_sweep_files(o, r, command);
        std::cout << "rrc-sweep: " << r.rrc.size() << " rrc rows, " << r.brute.size() << " brute-force rows in " << (int)r.seconds << " s; files in "
                  << o.out << "\n";
        if (o.validation && r.validation_messages) {
            std::cerr << "rrc-sweep: " << r.validation_messages << " validation message(s)\n";
            return 1;
        }
        if (o.plots) {
            // The plots and the verdicts: matplotlib (Debian's python3-matplotlib).
            const std::string py = std::string(RRC_SWEEP_PYTHON) + " '" + RRC_SWEEP_FRONTS_PY + "' '" + o.out + "'";
            if (std::system(py.c_str()) != 0) {
                std::cerr << "rrc-sweep: fronts.py failed (" << py << ")\n";
                return 1;
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "rrc-sweep: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
