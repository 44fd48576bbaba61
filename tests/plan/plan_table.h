// The plan table: the frame plan (plugin/frame_plan.cpp) of every rrc-bench
// configuration and call, one text.  tests/plan/plan_table_test.cpp compares
// it with the checked-in tests/plan/plan_table.txt; write_plan_table.cpp
// (target regenerate_plan_table) rewrites that file after an intended change.
#pragma once

#include <string>

namespace rrc_plan {

std::string plan_table();

}  // namespace rrc_plan
