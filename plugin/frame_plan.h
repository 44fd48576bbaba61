// The frame plan: from a context's configuration and what one call asks
// (initialise, run a frame, classify, resolve; on which path; which host
// outputs), every command the call records, in order: debug labels, the
// first use's initialisation, barriers, clears, uploads and readbacks, and
// the passes' dispatches with the set each binds and the grid it runs over.
// Steps name resources by id (PlanResource); a context only maps the ids to
// its images and buffers (PlanResources), and the core records the steps
// (AccumulatorCore::record_call, the planner's one caller a call).  The
// words: docs/design/frame-plan.md.
#pragma once

#include "accumulate_pipeline.h"
#include "config.h"

#include <string>
#include <vector>

namespace rrc {

// The API call a plan records: the context's one-time initialisation, a
// frame (rrc_frame_run, rrc_vulkan_record_frame), or a shading cache's split.
enum class PlanCall { Initialise, Run, Classify, Resolve };

struct PlanRequest {
    PlanCall call = PlanCall::Run;
    bool interop = false;
    bool first_use = false;      // interop: the library's images are not yet initialised (the host's first call)
    bool split_outputs = false;  // interop: rrc_vulkan_frame_desc.split_outputs
    bool host_mask = false;      // interop: the frame has a host mask image
    uint32_t host_age_mask = 0;  // interop: bit c, channel c has a host age image
    bool stats = false;          // interop: the frame has a statistics buffer
    bool count_io = false;       // interop, with stats: rrc_vulkan_frame_desc.count_io (Run only)
};

// What a step acts on.  The fill list and the view buffer are the core's
// own; the rest a context maps (PlanResources).
enum class PlanResource {
    Memory,           // a global memory barrier: every resource
    LibraryImages,    // every image the library owns (initialised to zero, GENERAL)
    FillList,         // the fill list's header (the indirect dispatch and the sub-lists' counts)
    ViewBuffer,       // the view lobe's camera
    QuadList,         // classify's quad list (interop: the host's buffer)
    Stats,            // interop: the host's statistics buffer
    HostImagesIn,     // interop: the host's images this call binds, to the kernel's layouts
    HostImagesOut,    // interop: the same, back to the host's final layouts
    Inputs,           // standalone: the library's copies of this call's inputs
    Outputs,          // standalone: the images this call reads back
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
    enum class Kind {
        BeginLabel,  // vkCmdBeginDebugUtilsLabelEXT(label), where the device has debug utils
        EndLabel,
        Initialise,  // LibraryImages: UNDEFINED -> GENERAL, cleared to zero
        Barrier,     // vkCmdPipelineBarrier over `resource` (Memory: a memory barrier)
        Clear,       // vkCmdUpdateBuffer: `resource`'s first words := `words`
        WriteView,   // vkCmdUpdateBuffer: the view buffer := the frame's camera
        Upload,      // Inputs: vkCmdCopyBufferToImage from staging, one an image
        Readback,    // Outputs: vkCmdCopyImageToBuffer into staging, one an image
        Dispatch,    // a pass: vkCmdDispatch, or vkCmdDispatchIndirect from the list `grid` names
    } kind = Kind::Dispatch;
    PlanResource resource = PlanResource::Memory;
    const char* label = nullptr;  // BeginLabel
    // Barrier: stages and accesses; Inputs and Outputs: their layouts too
    // (the host's images carry their own layouts and accesses: PlanResources).
    VkPipelineStageFlags src_stages = 0, dst_stages = 0;
    VkAccessFlags src_access = 0, dst_access = 0;
    VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED, new_layout = VK_IMAGE_LAYOUT_UNDEFINED;
    std::vector<uint32_t> words;  // Clear
    KernelVariant variant;        // Dispatch: the pipeline (pass, host outputs, statistics)
    PlanSet set = PlanSet::Frame;
    PlanGrid grid = PlanGrid::Pixels;
};

// What a context binds into a set beyond the library's own images.
struct PlanSetContents {
    bool used = false;
    bool channel_inputs = false;  // Frame: the frame's samples and confidences (classify reads the geometry only)
    bool fallbacks = false;       // the fallback estimates: the fill's (Next), a residual's base (Frame)
    bool host_mask = false;       // the host's mask image at RRC_BINDING_MASK (else the library's)
    uint32_t host_outputs = 0;    // bit c: channel c's host output image
    uint32_t host_ages = 0;       // bit c: channel c's host age image
    bool stats = false;           // the host's statistics buffer
    bool quad_list = false;       // the call's quad list
};

struct FramePlan {
    std::vector<PlanStep> steps;
    PlanSetContents sets[2];  // [PlanSet]
    bool count_io = false;    // the statistics buffer's range holds rrc_vulkan_io_counts too
    bool uses(PlanSet set) const { return sets[(int)set].used; }
};

FramePlan make_plan(const ContextConfig& config, const PlanRequest& request);

// One line a step, for the checked-in plan table (tests/plan): labels,
// barriers with their stages and accesses, clears, copies, and passes with
// their sets, bindings and dispatch sizes ("indirect" where the data decides).
std::string describe_plan(const FramePlan& plan, const ContextConfig& config);
const char* pass_name(uint32_t pass);

// Every channel is REUSE: the shading cache's proportional split applies.
bool all_reuse(const ContextConfig& config);

}  // namespace rrc
