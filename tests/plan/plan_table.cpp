// The plan table: every rrc-bench configuration's frame plan, as the checked-in
// tests/plan/plan_table.txt holds it (plan_table.h).
#include "plan/plan_table.h"

#include "bench/config.h"         // the rrc-bench configurations
#include "bench/context_setup.h"  // and their descriptors
#include "frame_plan.h"  // plugin/
#include "validation.h"  // plugin/: resolve_context_desc

#include <algorithm>
#include <sstream>
#include <vector>

namespace rrc_plan {
namespace {

// The library's configuration of an rrc-bench row: the bench's own
// descriptor (bench/context_setup.cpp) as the library reads it.
rrc::ContextConfig context_config(const rrc_bench::Config& b) {
    rrc_bench::LogCounter log;
    rrc_bench::ContextSetup setup(b, log);
    return rrc::resolve_context_desc(setup.desc());
}

}  // namespace

std::map<std::string, std::string> plan_texts() {
    std::map<std::string, std::string> texts;
    for (rrc_bench::Config b : rrc_bench::full_sweep()) {
        b.width = kWidth, b.height = kHeight;
        const rrc::ContextConfig c = context_config(b);
        std::vector<std::pair<const char*, rrc::PlanCall>> calls;
        switch (b.shading_cache) {
            case rrc_bench::Config::Cache::Split: calls = {{"classify", rrc::PlanCall::Classify}, {"resolve", rrc::PlanCall::Resolve}}; break;
            case rrc_bench::Config::Cache::ClassifyFused:
                calls = {{"classify", rrc::PlanCall::Classify}, {"frame", rrc::PlanCall::Run}};
                break;
            default: calls = {{"frame", rrc::PlanCall::Run}};
        }
        // The Vulkan path: the bench gives the host's mask and age images, and
        // a statistics buffer to its last frame only, which also counts the image
        // operations (count_io) where the frame is rrc_vulkan_record_frame alone.
        for (bool stats : {false, true})
            for (const auto& call : calls) {
                rrc::PlanRequest r;
                r.interop = true;
                r.host_mask = true;
                r.host_age_mask = (1u << c.channels.size()) - 1u;
                r.split_outputs = b.shading_cache == rrc_bench::Config::Cache::Split && b.split_outputs;  // bench/interop_run.cpp
                r.stats = stats;
                r.count_io = stats && b.records_frame_only();  // bench/interop_run.cpp
                r.call = call.second;
                texts[b.name + "/interop/" + call.first + (stats ? "+stats" : "")] = rrc::describe_plan(rrc::make_plan(c, r), c);
            }
        // The standalone path: the same calls (bench/standalone_run.cpp).
        rrc::PlanRequest r;
        for (const auto& call : calls) {
            r.call = call.second;
            texts[b.name + "/standalone/" + call.first] = rrc::describe_plan(rrc::make_plan(c, r), c);
        }
        r.call = rrc::PlanCall::Initialise;
        texts[b.name + "/standalone/initialise"] = rrc::describe_plan(rrc::make_plan(c, r), c);
    }
    return texts;
}

std::string plan_table() {
    // Each distinct plan once, with the calls that record it, in the sweep's order.
    std::vector<std::pair<std::string, std::vector<std::string>>> shapes;
    std::vector<std::string> order;
    for (rrc_bench::Config b : rrc_bench::full_sweep()) order.push_back(b.name + "/");
    const std::map<std::string, std::string> texts = plan_texts();
    for (const std::string& prefix : order)
        for (const auto& t : texts) {
            if (t.first.compare(0, prefix.size(), prefix) != 0) continue;
            auto found = std::find_if(shapes.begin(), shapes.end(), [&](const auto& s) { return s.first == t.second; });
            if (found == shapes.end()) shapes.push_back({t.second, {t.first}});
            else found->second.push_back(t.first);
        }
    std::ostringstream out;
    out << "# The frame plan of each rrc-bench configuration at " << kWidth << "x" << kHeight
        << ", each distinct plan once (tests/plan/plan_table_test.cpp;\n"
        << "# tests/plan/plan_capture_test.cpp checks that the contexts record exactly these commands).  Keys:\n"
        << "# configuration/path/call, +stats with the host's statistics buffer (and, on a frame call alone, the\n"
        << "# image operations counted).  The host's first call on the\n"
        << "# Vulkan path also initialises the library's images, right after its label.\n";
    int n = 0;
    for (const auto& shape : shapes) {
        out << "\n## plan " << ++n << " (" << shape.second.size() << " calls)\n";
        std::string line;
        for (const std::string& key : shape.second) {
            if (line.size() + key.size() > 110) out << line << "\n", line.clear();
            line += (line.empty() ? "" : " ") + key;
        }
        out << line << "\n" << shape.first;
    }
    return out.str();
}

}  // namespace rrc_plan
