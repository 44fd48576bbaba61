// The state and the recording both contexts share: the device wrapper, the
// passes' pipelines, the placeholders, the library-owned mask, and per
// view the previous depth, each channel's history and the ping-pong parity.
// A context differs from another only in where its input images come from
// (its own uploads, or the host's images) and how work is submitted.
#pragma once

#include "accumulate_pipeline.h"
#include "channel_history.h"
#include "config.h"
#include "frame.h"
#include "frame_plan.h"
#include "plan_resources.h"
#include "gpu_resources.h"
#include "live_inputs.h"
#include "vulkan_device.h"

#include <functional>
#include <memory>
#include <vector>

namespace rrc {

// What one view (the camera, a stereo eye, a motion-blur sub-frame, a lens
// sample) carries from frame to frame.  A frame writes its view's `parity`
// set and reads its source's latest (rrc_frame_desc.reproject_from): its own
// other parity, or another view's last written set.
struct ViewState {
    GpuImage depth[2];      // [parity]: this frame's depth; the other parity is the previous frame's
    GpuImage object_id[2];  // the same for object ids (R32_UINT), when the context uses them
    std::vector<std::unique_ptr<ChannelHistory>> channels;
    uint32_t parity = 0;         // the image set the next frame writes
    bool have_previous = false;  // false: first frame, or after a failed creation
    uint64_t frame_index = 0;    // the last submitted frame's index (refresh clocks)
};

class AccumulatorCore {
public:
    // sets: descriptor sets the pipeline's pool holds.
    AccumulatorCore(std::unique_ptr<VulkanDevice> device, const ContextConfig& config, bool interop, uint32_t sets,
                    VkPipelineCache cache = VK_NULL_HANDLE);
    ~AccumulatorCore();
    AccumulatorCore(const AccumulatorCore&) = delete;
    AccumulatorCore& operator=(const AccumulatorCore&) = delete;

    const ContextConfig& config() const { return config_; }
    VulkanDevice& device() { return *dev_; }
    const VulkanDevice& device() const { return *dev_; }
    AccumulatePipeline& pipeline() { return pipeline_; }
    const std::vector<LiveInput>& inputs() const { return inputs_; }
    ViewState& view(uint32_t v = 0) { return views_[v]; }
    const ViewState& view(uint32_t v = 0) const { return views_[v]; }
    uint32_t view_count() const { return (uint32_t)views_.size(); }
    // The parity holding a view's latest frame.
    static uint32_t latest(const ViewState& v) { return 1 - v.parity; }
    const GpuImage& own_mask() const { return mask_; }

    // Every binding of the frame that writes `parity` of `view`: the
    // library's own images (previous depth, histories, mask) over
    // placeholders.  The caller adds its inputs (and, interop, outputs).
    DescriptorViews library_views(const ViewState& view, uint32_t parity) const { return library_views(view, parity, view, 1 - parity); }
    // The same for a frame that reprojects from `source`'s set `source_parity`.
    DescriptorViews library_views(const ViewState& view, uint32_t parity, const ViewState& source, uint32_t source_parity) const;
    // Records one call: makes its plan (the only caller of make_plan), every
    // pipeline the plan dispatches (base: the frame's own variant bits, e.g.
    // storage_inputs) before anything is recorded, so that a failure leaves
    // the command buffer untouched; then asks `map` for the resources the
    // plan's ids stand for, and records the steps.  frame: NULL for Initialise.
    using MapResources = std::function<PlanResources(const FramePlan&)>;
    void record_call(VkCommandBuffer cmd, const PlanRequest& request, const KernelVariant& base, const Frame* frame, bool prev_valid,
                     const MapResources& map);
    // After `count` frames were recorded (standalone: and submitted).
    void advance(ViewState& view, uint32_t count, uint64_t last_frame_index);
    size_t memory_bytes() const;

private:
    void prepare(const FramePlan& plan, const KernelVariant& base);
    void record_steps(VkCommandBuffer cmd, const FramePlan& plan, const PlanResources& res, const KernelVariant& base, const Frame* frame,
                      bool prev_valid);
    void record_barrier(VkCommandBuffer cmd, const PlanStep& step, const PlanResources& res) const;

    // Declaration order is destruction order reversed: every Vulkan object
    // goes before the device wrapper that destroys the device.
    ContextConfig config_;
    std::unique_ptr<VulkanDevice> dev_;
    std::vector<LiveInput> inputs_;
    AccumulatePipeline pipeline_;
    Placeholders placeholders_;
    std::vector<ViewState> views_;
    GpuImage mask_;                 // standalone: always bound; interop: when the host gives no mask
    HostBuffer stats_placeholder_;  // bound when no frame statistics are asked for
    HostBuffer quads_placeholder_;  // bound where no quad list is written
    HostBuffer fill_list_;          // the spatial fill's pixels (rrc_kernel_interface.h); a placeholder without a fill
    HostBuffer view_buffer_;        // the view lobe's camera (rrc_kernel_interface.h, RRC_BINDING_VIEW); never written without one
};

}  // namespace rrc
