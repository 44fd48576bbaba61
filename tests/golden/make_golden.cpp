// rrc-make-golden DIR: writes the golden EXR files of golden_cases.h into
// DIR (tests/data in the repository) from the analytic scenes and the
// double-precision reference.  No GPU involved.
#include "golden/golden_io.h"

#include <cstdio>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: rrc-make-golden DIR\n");
        return 2;
    }
    try {
        for (const auto& c : rrc_golden::golden_cases()) {
            std::string path = rrc_golden::golden_file(argv[1], c);
            rrc_golden::write_golden(path, c, rrc_golden::compute_golden(c));
            std::printf("wrote %s\n", path.c_str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rrc-make-golden: %s\n", e.what());
        return 1;
    }
    return 0;
}
