// The frame plan of every rrc-bench configuration, against the checked-in
// table tests/plan/plan_table.txt: one file says what any configuration runs
// (passes, the bindings each reads and writes, barriers, dispatch sizes or
// "indirect" where the data decides; docs/PERFORMANCE.md, "The frame plan").
// The plan (plugin/frame_plan.cpp) is compiled into this test: it is pure
// C++ on the context's configuration, no device involved.
//
// After an intended change of a plan, regenerate the table:
//   RRC_WRITE_PLAN_TABLE=1 build/release/tests/rrc_plan_table_test
#include "bench/config.h"  // the rrc-bench configurations
#include "frame_plan.h"  // plugin/

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

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

std::string table() {
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

TEST(PlanTable, EveryBenchConfigurationRunsWhatTheTableSays) {
    const std::string path = std::string(RRC_PLAN_TABLE);
    const std::string now = table();
    if (std::getenv("RRC_WRITE_PLAN_TABLE")) {
        std::ofstream(path) << now;
        GTEST_SKIP() << "wrote " << path;
    }
    std::ifstream in(path);
    ASSERT_TRUE(in) << "no table at " << path;
    std::stringstream checked;
    checked << in.rdbuf();
    // Line by line, so a failure names the first line that moved.
    std::istringstream a(checked.str()), b(now);
    std::string la, lb;
    int line = 0;
    while (true) {
        const bool ga = (bool)std::getline(a, la), gb = (bool)std::getline(b, lb);
        ++line;
        if (!ga && !gb) break;
        ASSERT_EQ(ga, gb) << "the table and the plans differ in length at line " << line;
        ASSERT_EQ(la, lb) << "line " << line << " of " << path << " (regenerate with RRC_WRITE_PLAN_TABLE=1 if intended)";
    }
}

// What the table must show, whatever its wording: the proportional passes.
TEST(PlanTable, ShadingCacheResolveAndFillAreIndirect) {
    rrc::ContextConfig c;
    c.width = 64, c.height = 32;
    rrc::ChannelConfig reuse;
    reuse.blend = RRC_BLEND_REUSE;
    c.channels = {reuse};
    rrc::PlanRequest r;
    r.call = rrc::PlanCall::Resolve;
    r.interop = true;
    r.split_outputs = true;
    rrc::FramePlan p = rrc::make_plan(c, r);
    ASSERT_EQ(p.steps.size(), 1u);
    EXPECT_EQ(p.steps[0].variant.phase, RRC_PHASE_RESOLVE_LISTED);
    EXPECT_EQ(p.steps[0].grid, rrc::PlanGrid::QuadList);
    r.split_outputs = false;  // the host's images get a copy of every pixel
    p = rrc::make_plan(c, r);
    ASSERT_EQ(p.steps.size(), 3u);
    EXPECT_EQ(p.steps[2].variant.phase, RRC_PHASE_COPY_OUT);
    EXPECT_EQ(p.steps[2].grid, rrc::PlanGrid::Pixels);
    // An accumulating channel: resolve over every pixel, the fill over its list.
    c.channels[0].blend = RRC_BLEND_FIXED;
    c.channels[0].fill_age = 8;
    p = rrc::make_plan(c, r);
    ASSERT_EQ(p.steps.size(), 4u);
    EXPECT_EQ(p.steps[0].op, rrc::PlanStep::Op::ClearFillList);
    EXPECT_EQ(p.steps[1].variant.phase, RRC_PHASE_RESOLVE);
    EXPECT_TRUE(p.steps[2].op == rrc::PlanStep::Op::Barrier && p.steps[2].to_indirect);
    EXPECT_EQ(p.steps[3].variant.phase, RRC_PHASE_FILL);
    EXPECT_EQ(p.steps[3].grid, rrc::PlanGrid::FillList);
    EXPECT_EQ(p.steps[3].set, rrc::PlanSet::Next);
}

// A view lobe (docs/CONVENTIONS.md, "The view-dependent history"): the calls
// that carry a frame write the view buffer first; resolve reads what classify
// wrote; without a lobe no plan writes it.
TEST(FramePlan, AViewLobeWritesTheViewBufferBeforeTheFramesPasses) {
    rrc::ContextConfig c;
    c.width = 64, c.height = 32;
    rrc::ChannelConfig ch;
    ch.blend = RRC_BLEND_AGE_AWARE;
    c.channels = {ch};
    auto writes_view = [](const rrc::FramePlan& p) {
        for (const rrc::PlanStep& s : p.steps)
            if (s.op == rrc::PlanStep::Op::WriteView) return true;
        return false;
    };
    for (rrc::PlanCall call : {rrc::PlanCall::Run, rrc::PlanCall::Classify, rrc::PlanCall::Resolve}) {
        rrc::PlanRequest r;
        r.call = call;
        EXPECT_FALSE(writes_view(rrc::make_plan(c, r))) << "no lobe";
    }
    c.channels[0].view_lobe = 0.05f;
    for (rrc::PlanCall call : {rrc::PlanCall::Run, rrc::PlanCall::Classify}) {
        rrc::PlanRequest r;
        r.call = call;
        const rrc::FramePlan p = rrc::make_plan(c, r);
        ASSERT_FALSE(p.steps.empty());
        EXPECT_EQ(p.steps[0].op, rrc::PlanStep::Op::WriteView) << "before every dispatch";
        EXPECT_NE(rrc::describe_plan(p, c).find("write view buffer"), std::string::npos);
    }
    rrc::PlanRequest r;
    r.call = rrc::PlanCall::Resolve;
    EXPECT_FALSE(writes_view(rrc::make_plan(c, r))) << "resolve keeps classify's camera";
}

}  // namespace
