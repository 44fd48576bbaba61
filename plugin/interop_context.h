// A context on the host's Vulkan device: records each call's plan into the
// host's command buffer, never submits or waits.  Over
// the shared accumulator core it adds only what this path needs: the host's
// images bound per frame, the barriers that hand them over and back, the
// descriptor-set ring of the frames in flight, and the statistics buffer.
#pragma once

#include "accumulator_core.h"
#include "frame.h"

#include <rrc/rrc_vulkan.h>

#include <map>
#include <memory>
#include <vector>

namespace rrc {

class InteropContext {
public:
    InteropContext(const ContextConfig& config, const rrc_vulkan_device_desc& device);
    ~InteropContext();

    // Records an already validated frame.
    void record_frame(const Frame& frame);
    // The shading cache's split frame: classify into the host's list, then
    // resolve (refused without a classify of the same frame index).
    void record_classify(const Frame& frame, VkBuffer list, VkDeviceSize list_offset);
    void record_resolve(const Frame& frame);

    const ContextConfig& config() const { return core_->config(); }
    const VulkanDevice& device() const { return core_->device(); }
    size_t memory_bytes() const { return core_->memory_bytes(); }
    // The device's minStorageBufferOffsetAlignment (validation of stats_offset).
    uint64_t stats_alignment() const { return stats_alignment_; }

private:
    // One call's frame plan; list: classify's quad list (resolve: the pending classify's).
    void record_pass(const Frame& frame, PlanCall call, VkBuffer list = VK_NULL_HANDLE, VkDeviceSize list_offset = 0);
    DescriptorSets next_set();  // the ring's next

    std::unique_ptr<AccumulatorCore> core_;
    std::vector<DescriptorSets> ring_;  // four sets (two calls, two sets each) per frame in flight, plus four
    uint32_t next_set_ = 0;
    uint64_t stats_alignment_ = 0;
    // The classify recorded last, until its resolve (any other frame drops it).
    struct Pending {
        bool valid = false;
        uint64_t frame_index = 0;
        uint32_t view = 0, reproject_from = 0;
        VkBuffer list = VK_NULL_HANDLE;  // its quad list: a shading cache's resolve is dispatched from it
        VkDeviceSize list_offset = 0;
    } pending_;
    bool initialised_ = false;  // images cleared and in GENERAL (recorded with the first frame)
};

}  // namespace rrc
