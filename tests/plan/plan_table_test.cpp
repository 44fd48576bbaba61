// The frame plan of every rrc-bench configuration, against the checked-in
// table tests/plan/plan_table.txt: one file says what any configuration runs
// (passes, the bindings each reads and writes, barriers, dispatch sizes or
// "indirect" where the data decides; docs/PERFORMANCE.md, "The frame plan").
// The plan (plugin/frame_plan.cpp) is compiled into this test: it is pure
// C++ on the context's configuration, no device involved.
//
// After an intended change of a plan, regenerate the table with its own
// program (tests/plan/write_plan_table.cpp), never from this test:
//   cmake --build build/release --target regenerate_plan_table
#include "frame_plan.h"  // plugin/
#include "plan/plan_table.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace {

TEST(PlanTable, EveryBenchConfigurationRunsWhatTheTableSays) {
    const std::string path = std::string(RRC_PLAN_TABLE);
    const std::string now = rrc_plan::plan_table();
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
        ASSERT_EQ(la, lb) << "line " << line << " of " << path << " (if intended: cmake --build <build> --target regenerate_plan_table)";
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
