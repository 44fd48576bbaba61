// The plan table: the frame plan (plugin/frame_plan.cpp) of every rrc-bench
// configuration at a small size, on both paths, for each call the bench
// makes (with and without a statistics buffer on the Vulkan path), printed
// once per distinct plan.  tests/plan/plan_table_test.cpp compares it with
// the checked-in tests/plan/plan_table.txt; write_plan_table.cpp (target
// regenerate_plan_table) rewrites that file after an intended change;
// plan_capture_test.cpp checks that the contexts record what it says.
#pragma once

#include <map>
#include <string>

namespace rrc_plan {

// The size every configuration is planned (and captured) at.
constexpr unsigned kWidth = 64, kHeight = 32;

// By "<configuration>/<interop|standalone>/<call>[+stats]": describe_plan's
// text of that call's plan; "initialise" for the standalone path's creation.
std::map<std::string, std::string> plan_texts();
std::string plan_table();

}  // namespace rrc_plan
