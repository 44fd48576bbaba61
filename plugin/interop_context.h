// A context on the host's Vulkan device: records its barriers and one
// dispatch into the host's command buffer, never submits or waits.  Owns
// only what persists between frames: history, ages, weights, the previous
// depth (ping-pong) and a mask when the host gives none.
#pragma once

#include "accumulate_pipeline.h"
#include "channel_history.h"
#include "config.h"
#include "gpu_resources.h"
#include "vulkan_device.h"

#include <rrc/rrc_vulkan.h>

#include <memory>
#include <vector>

namespace rrc {

class InteropContext {
public:
    InteropContext(const ContextConfig& config, const rrc_vulkan_device_desc& device);
    ~InteropContext();

    // Validates the frame against the configuration (throws rrc::Error before
    // recording anything) and records it.
    void record_frame(const rrc_vulkan_frame_desc& frame);

    const ContextConfig& config() const { return config_; }
    const VulkanDevice& device() const { return *dev_; }
    size_t memory_bytes() const;

private:
    void validate(const rrc_vulkan_frame_desc& frame) const;
    void record_initialisation(VkCommandBuffer cmd);

    ContextConfig config_;
    std::unique_ptr<VulkanDevice> dev_;
    std::unique_ptr<AccumulatePipeline> pipeline_;
    std::unique_ptr<Placeholders> placeholders_;
    GpuImage depth_[2];  // [parity]: written by the frame of that parity, read as previous by the next
    GpuImage mask_;      // used when the host passes no mask image
    std::vector<std::unique_ptr<ChannelHistory>> channels_;
    std::vector<VkDescriptorSet> ring_;  // one set per frame in flight
    uint32_t next_set_ = 0;
    uint32_t parity_ = 0;
    bool have_previous_ = false;
    bool initialised_ = false;  // images cleared and in GENERAL (recorded with the first frame)
};

}  // namespace rrc
