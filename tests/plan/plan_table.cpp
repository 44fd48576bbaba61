// The plan table: every rrc-bench configuration's frame plan, as the checked-in
// tests/plan/plan_table.txt holds it (plan_table.h).
#include "plan/plan_table.h"

#include "bench/config.h"  // the rrc-bench configurations
#include "frame_plan.h"    // plugin/

#include <sstream>

namespace rrc_plan {
namespace {

// The library's configuration of an rrc-bench row (bench/context_setup.cpp
// builds the same through the public API).
rrc::ContextConfig context_config(const rrc_bench::Config& b) {
    rrc::ContextConfig c;
    c.width = b.width;
    c.height = b.height;
    for (const rrc_bench::ChannelConfig& bc : b.channels) {
        rrc::ChannelConfig ch;
        ch.components = bc.components;
        ch.fp16 = bc.precision != RRC_HISTORY_FP32;
        ch.blend = b.shading_cache != rrc_bench::Config::Cache::Off ? RRC_BLEND_REUSE : RRC_BLEND_FIXED;
        ch.fill_age = bc.fill_age;
        ch.view_lobe = bc.view_lobe;
        if (bc.fill_radius) ch.fill_radius = bc.fill_radius;
        c.channels.push_back(ch);
    }
    return c;
}

}  // namespace

std::string plan_table() {
    std::ostringstream out;
    out << "# The frame plan of each rrc-bench configuration (tests/plan/plan_table_test.cpp).\n"
        << "# Timed frames pass no statistics buffer; the bench gives the host's mask and age images.\n";
    for (const rrc_bench::Config& b : rrc_bench::full_sweep()) {
        const rrc::ContextConfig c = context_config(b);
        rrc::PlanRequest r;
        r.interop = !b.standalone;
        r.host_mask = r.interop;
        r.host_age_mask = r.interop ? (1u << c.channels.size()) - 1u : 0u;
        r.split_outputs = b.split_outputs;
        std::vector<std::pair<const char*, rrc::PlanCall>> calls;
        switch (b.shading_cache) {
            case rrc_bench::Config::Cache::Split: calls = {{"classify", rrc::PlanCall::Classify}, {"resolve", rrc::PlanCall::Resolve}}; break;
            case rrc_bench::Config::Cache::ClassifyFused:
                calls = {{"classify", rrc::PlanCall::Classify}, {"frame", rrc::PlanCall::Run}};
                break;
            default: calls = {{"frame", rrc::PlanCall::Run}};
        }
        out << "\n## " << b.name << " (" << b.width << "x" << b.height << ", " << rrc_bench::channels_text(b)
            << (r.interop ? ", interop" : ", standalone") << (b.shading_cache != rrc_bench::Config::Cache::Off ? ", REUSE" : "")
            << (b.shading_cache == rrc_bench::Config::Cache::Split ? (b.split_outputs ? ", split_outputs" : ", no split_outputs") : "")
            << ")\n";
        for (const auto& call : calls) {
            r.call = call.second;
            out << call.first << ":\n" << rrc::describe_plan(rrc::make_plan(c, r), c);
        }
    }
    return out.str();
}

}  // namespace rrc_plan
