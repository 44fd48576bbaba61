// The frame plan: from a context's configuration and what one call asks
// (run a frame, classify, resolve; on which path; which host outputs), the
// passes it runs, in order, with the barrier before each, the descriptor set
// each is bound with and the grid it runs over.  Both contexts only execute
// a plan (AccumulatorCore::record_plan); the order of passes lives here and
// nowhere else (docs/PERFORMANCE.md, "The frame plan").
#pragma once

#include "accumulate_pipeline.h"
#include "config.h"

#include <string>
#include <vector>

namespace rrc {

enum class PlanCall { Run, Classify, Resolve };

struct PlanRequest {
    PlanCall call = PlanCall::Run;
    bool interop = false;
    bool split_outputs = false;  // interop: rrc_vulkan_frame_desc.split_outputs
    bool host_mask = false;      // interop: the frame has a host mask image
    uint32_t host_age_mask = 0;  // interop: bit c, channel c has a host age image
    bool stats = false;          // interop: the frame has a statistics buffer
};

// Which descriptor set a pass is bound with.
enum class PlanSet {
    Frame,  // the frame's: its inputs, the history it reads and writes
    Next,   // bound as the next frame would be: this frame's results as history inputs
};

// What a pass runs over: a direct dispatch over pixels or 2x2 quads, or an
// indirect one whose size the data decides (the quad list, the fill list).
enum class PlanGrid { Pixels, Quads, QuadList, FillList };

struct PlanStep {
    enum class Op {
        ClearFillList,  // the fill list's count and dispatch to {0, 0, 1, 1} (a transfer, with its barriers)
        WriteView,      // the view buffer from the frame's camera (a transfer, with its barriers; contexts with a view lobe)
        Barrier,        // the previous pass's writes to the next pass's reads (and, to_indirect, its indirect read)
        Dispatch,
    } op = Op::Dispatch;
    KernelVariant variant;  // Dispatch: the pipeline (phase, host outputs, statistics)
    PlanSet set = PlanSet::Frame;
    PlanGrid grid = PlanGrid::Pixels;
    bool to_indirect = false;  // Barrier: the next dispatch is indirect
};

struct FramePlan {
    std::vector<PlanStep> steps;
    // Where the Frame set binds the mask: the host's image (true) or the
    // library's own.  Classify writes its mask there, and the passes after
    // it read it in place (KernelVariant::mask_in_place) where resolve's set binds the same image.
    bool frame_set_host_mask = false;
    bool uses(PlanSet set) const;
};

FramePlan make_plan(const ContextConfig& config, const PlanRequest& request);

// One line a step, for the checked-in plan table (tests/plan): passes,
// bindings, barriers and dispatch sizes ("indirect" where the data decides).
std::string describe_plan(const FramePlan& plan, const ContextConfig& config);

// Every channel is REUSE: the shading cache's proportional split applies.
bool all_reuse(const ContextConfig& config);

}  // namespace rrc
