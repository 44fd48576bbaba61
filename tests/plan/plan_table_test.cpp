// The frame plan of every rrc-bench configuration, against the checked-in
// table tests/plan/plan_table.txt: one file says what any configuration runs
// (passes, the bindings each reads and writes, barriers, dispatch sizes or
// "indirect" where the data decides; docs/design/frame-plan.md).
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

using Kind = rrc::PlanStep::Kind;

std::vector<rrc::PlanStep> of_kind(const rrc::FramePlan& p, Kind kind) {
    std::vector<rrc::PlanStep> out;
    for (const rrc::PlanStep& s : p.steps)
        if (s.kind == kind) out.push_back(s);
    return out;
}

size_t index_of(const rrc::FramePlan& p, Kind kind, size_t from = 0) {
    for (size_t i = from; i < p.steps.size(); ++i)
        if (p.steps[i].kind == kind) return i;
    return p.steps.size();
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
    std::vector<rrc::PlanStep> d = of_kind(rrc::make_plan(c, r), Kind::Dispatch);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].variant.pass, RRC_PASS_RESOLVE_LISTED);
    EXPECT_EQ(d[0].grid, rrc::PlanGrid::QuadList);
    r.split_outputs = false;  // the host's images get a copy of every pixel
    d = of_kind(rrc::make_plan(c, r), Kind::Dispatch);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[1].variant.pass, RRC_PASS_COPY_OUT);
    EXPECT_EQ(d[1].grid, rrc::PlanGrid::Pixels);
    EXPECT_EQ(d[1].set, rrc::PlanSet::Next);
    // An accumulating channel: resolve over every pixel, the fill over its
    // list, which is cleared before the first pass; an indirect read waits for its writes.
    c.channels[0].blend = RRC_BLEND_FIXED;
    c.channels[0].fill_age = 8;
    const rrc::FramePlan p = rrc::make_plan(c, r);
    d = of_kind(p, Kind::Dispatch);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[0].variant.pass, RRC_PASS_RESOLVE);
    EXPECT_EQ(d[1].variant.pass, RRC_PASS_FILL);
    EXPECT_EQ(d[1].grid, rrc::PlanGrid::FillList);
    EXPECT_EQ(d[1].set, rrc::PlanSet::Next);
    const size_t clear = index_of(p, Kind::Clear), first = index_of(p, Kind::Dispatch), fill = index_of(p, Kind::Dispatch, first + 1);
    ASSERT_LT(clear, first);
    EXPECT_EQ(p.steps[clear].resource, rrc::PlanResource::FillList);
    const rrc::PlanStep& before_fill = p.steps[fill - 1];
    EXPECT_EQ(before_fill.kind, Kind::Barrier);
    EXPECT_TRUE(before_fill.dst_stages & VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT);
    EXPECT_TRUE(before_fill.dst_access & VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
}

// The whole call: a label around it; the first use's initialisation and the
// history barrier before anything else; the host's images handed over before
// the first dispatch and back after the last; classify's list cleared before
// and handed to the host after; the statistics cleared, and handed over last.
TEST(FramePlan, TheInteropPlanIsTheWholeCommandList) {
    rrc::ContextConfig c;
    c.width = 64, c.height = 32;
    rrc::ChannelConfig ch;
    c.channels = {ch};
    rrc::PlanRequest r;
    r.call = rrc::PlanCall::Classify;
    r.interop = true;
    r.first_use = true;
    r.stats = true;
    const rrc::FramePlan p = rrc::make_plan(c, r);
    ASSERT_GE(p.steps.size(), 6u);
    EXPECT_EQ(p.steps.front().kind, Kind::BeginLabel);
    EXPECT_EQ(p.steps.back().kind, Kind::EndLabel);
    EXPECT_EQ(p.steps[1].kind, Kind::Initialise);
    EXPECT_EQ(p.steps[2].kind, Kind::Barrier);
    EXPECT_EQ(p.steps[2].resource, rrc::PlanResource::Memory);
    const size_t first = index_of(p, Kind::Dispatch);
    size_t last = first;
    for (size_t i = first; i < p.steps.size(); ++i)
        if (p.steps[i].kind == Kind::Dispatch) last = i;
    auto where = [&](rrc::PlanResource res, Kind kind) {
        std::vector<size_t> at;
        for (size_t i = 0; i < p.steps.size(); ++i)
            if (p.steps[i].resource == res && p.steps[i].kind == kind) at.push_back(i);
        return at;
    };
    ASSERT_EQ(where(rrc::PlanResource::HostImagesIn, Kind::Barrier).size(), 1u);
    EXPECT_LT(where(rrc::PlanResource::HostImagesIn, Kind::Barrier)[0], first);
    ASSERT_EQ(where(rrc::PlanResource::HostImagesOut, Kind::Barrier).size(), 1u);
    EXPECT_GT(where(rrc::PlanResource::HostImagesOut, Kind::Barrier)[0], last);
    ASSERT_EQ(where(rrc::PlanResource::QuadList, Kind::Clear).size(), 1u);
    EXPECT_LT(where(rrc::PlanResource::QuadList, Kind::Clear)[0], first);
    const std::vector<size_t> list_barriers = where(rrc::PlanResource::QuadList, Kind::Barrier);
    ASSERT_EQ(list_barriers.size(), 3u) << "before and after its clear, and to the host";
    EXPECT_GT(list_barriers[2], last);
    EXPECT_TRUE(p.steps[list_barriers[2]].dst_access & VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
    ASSERT_EQ(where(rrc::PlanResource::Stats, Kind::Clear).size(), 1u);
    const std::vector<size_t> stats = where(rrc::PlanResource::Stats, Kind::Barrier);
    ASSERT_EQ(stats.size(), 3u);
    EXPECT_TRUE(p.steps[stats[2]].dst_access & VK_ACCESS_HOST_READ_BIT);
    EXPECT_TRUE(p.sets[(int)rrc::PlanSet::Frame].quad_list);
    EXPECT_FALSE(p.sets[(int)rrc::PlanSet::Frame].channel_inputs) << "classify reads the geometry only";
    // Resolve adds its counts to classify's: no clear.
    r.call = rrc::PlanCall::Resolve;
    r.first_use = false;
    const rrc::FramePlan resolve = rrc::make_plan(c, r);
    for (const rrc::PlanStep& s : resolve.steps) {
        EXPECT_FALSE(s.kind == Kind::Clear && s.resource == rrc::PlanResource::Stats);
        EXPECT_NE(s.kind, Kind::Initialise);
    }
}

// The standalone path: the call's inputs uploaded before the passes, its
// outputs read back after them and made visible to the host last.
TEST(FramePlan, TheStandalonePlanUploadsAndReadsBack) {
    rrc::ContextConfig c;
    c.width = 64, c.height = 32;
    c.channels = {rrc::ChannelConfig{}};
    rrc::PlanRequest r;
    const rrc::FramePlan p = rrc::make_plan(c, r);
    const size_t upload = index_of(p, Kind::Upload), first = index_of(p, Kind::Dispatch), readback = index_of(p, Kind::Readback);
    ASSERT_LT(upload, first);
    ASSERT_LT(first, readback);
    ASSERT_LT(readback, p.steps.size());
    EXPECT_EQ(p.steps[upload - 1].new_layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    EXPECT_EQ(p.steps[upload + 1].new_layout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(p.steps[readback - 1].new_layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    const rrc::PlanStep& last = p.steps[p.steps.size() - 2];
    EXPECT_EQ(last.kind, Kind::Barrier);
    EXPECT_EQ(last.dst_access, (VkAccessFlags)VK_ACCESS_HOST_READ_BIT);
    for (const rrc::PlanStep& s : p.steps) EXPECT_NE(s.resource, rrc::PlanResource::HostImagesIn);
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
    for (rrc::PlanCall call : {rrc::PlanCall::Run, rrc::PlanCall::Classify, rrc::PlanCall::Resolve}) {
        rrc::PlanRequest r;
        r.call = call;
        EXPECT_TRUE(of_kind(rrc::make_plan(c, r), Kind::WriteView).empty()) << "no lobe";
    }
    c.channels[0].view_lobe = 0.05f;
    for (rrc::PlanCall call : {rrc::PlanCall::Run, rrc::PlanCall::Classify}) {
        rrc::PlanRequest r;
        r.call = call;
        const rrc::FramePlan p = rrc::make_plan(c, r);
        ASSERT_LT(index_of(p, Kind::WriteView), index_of(p, Kind::Dispatch)) << "before every dispatch";
        EXPECT_NE(rrc::describe_plan(p, c).find("write view buffer"), std::string::npos);
    }
    rrc::PlanRequest r;
    r.call = rrc::PlanCall::Resolve;
    EXPECT_TRUE(of_kind(rrc::make_plan(c, r), Kind::WriteView).empty()) << "resolve keeps classify's camera";
}

}  // namespace
