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
#include "gpu_resources.h"
#include "live_inputs.h"
#include "vulkan_device.h"

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
    // Images to clear to zero and move to GENERAL once, before first use.
    void collect_images(std::vector<GpuImage*>& out);
    // The previous frame's kernel wrote what this one reads and read what
    // this one overwrites: one global barrier, compute -> compute.
    void record_history_barrier(VkCommandBuffer cmd, VkPipelineStageFlags extra_src_stages, VkAccessFlags extra_src_access) const;
    // The descriptor sets a plan's passes are bound with (PlanSet), and the
    // quad list RESOLVE_LISTED is dispatched from.
    struct PlanBindings {
        DescriptorSets frame, next;
        VkBuffer quad_list = VK_NULL_HANDLE;
        VkDeviceSize quad_list_offset = 0;
    };
    // Makes every pipeline the plan dispatches (base: the frame's own
    // variant bits, e.g. storage_inputs): call before recording anything, so
    // that a failure leaves the command buffer untouched.
    void prepare(const FramePlan& plan, const KernelVariant& base);
    // Records the plan's steps: push constants from the frame record.
    void record_plan(VkCommandBuffer cmd, const FramePlan& plan, const PlanBindings& sets, const KernelVariant& base, const Frame& frame,
                     bool prev_valid);
    // After `count` frames were recorded (standalone: and submitted).
    void advance(ViewState& view, uint32_t count, uint64_t last_frame_index);
    size_t memory_bytes() const;

private:
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
