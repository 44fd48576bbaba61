// Rewrites the checked-in plan table (tests/plan/plan_table.txt, or the path
// given) from the frame plans of every rrc-bench configuration: run after an
// intended change of a plan, then review the diff.  The test
// (plan_table_test.cpp) only compares; it never writes.
//   cmake --build build/release --target regenerate_plan_table
#include "plan/plan_table.h"

#include <cstdio>
#include <fstream>

int main(int argc, char** argv) {
    const char* path = argc > 1 ? argv[1] : RRC_PLAN_TABLE;
    std::ofstream out(path);
    out << rrc_plan::plan_table();
    if (!out) {
        std::fprintf(stderr, "write_plan_table: cannot write %s\n", path);
        return 1;
    }
    std::printf("write_plan_table: wrote %s\n", path);
    return 0;
}
