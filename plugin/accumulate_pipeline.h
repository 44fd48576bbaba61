// The fused kernel's pipeline: descriptor layout, specialization constants
// chosen from the context's configuration (so a scene pays only for what it
// enables) and the dispatch.  Binding numbers and constant ids mirror
// compute/rrc_accumulate.comp and compute/rrc_reproject.glsl.
#pragma once

#include "config.h"
#include "vulkan_device.h"

namespace rrc {

enum Binding : uint32_t {
    kDepth = 0,
    kPrevDepth = 1,
    kReproj = 2,
    kMotion = 3,
    kNocache = 4,
    kMask = 5,
    kHostDepth = 6,
    kHostReproj = 7,
    kHostNocache = 8,
    kDepthOut = 9,  // interop
    // per channel, arrays of RRC_MAX_CHANNELS
    kSample1 = 10,
    kSample4,
    kConfidence,
    kHistR16f,
    kHistRgba16f,
    kHistR32f,
    kHistRgba32f,
    kAge,
    kWeight,
    kHistOut,
    kAgeOut,
    kWeightOut,
    kHostSamples = 22,
    kHostConfidence = 23,
    kHostOut = 24,  // interop
};
constexpr uint32_t kFirstChannelBinding = kSample1, kLastBinding = kHostOut, kBindingCount = kLastBinding + 1;

// Sampled (combined image sampler) bindings; all others are storage images.
inline bool is_sampled_binding(uint32_t b) {
    return b == kHostDepth || b == kHostReproj || b == kHostNocache || b == kHostSamples || b == kHostConfidence;
}
inline uint32_t binding_count(uint32_t b) { return b >= kFirstChannelBinding ? RRC_MAX_CHANNELS : 1; }

// The image view bound at [binding][slot]; every entry must be filled
// (placeholders where a configuration does not use a binding).
struct DescriptorViews {
    VkImageView view[kBindingCount][RRC_MAX_CHANNELS] = {};
    VkImageLayout layout[kBindingCount][RRC_MAX_CHANNELS] = {};  // 0 = GENERAL
};

// Layout of `Frame` in compute/rrc_reproject.glsl.
struct FramePushConstants {
    float M[16];  // column-major
    float inv_row3[4];
    float jitter[4];
    float motion_scale[2];
    float eps;
    float near_plane, far_plane;
    float bg_threshold;
    uint32_t prev_valid;
};
static_assert(sizeof(FramePushConstants) == 124, "must match the GLSL push-constant block");

class AccumulatePipeline {
public:
    static constexpr uint32_t kGroupX = 128, kGroupY = 1;  // SPEC §8: wide groups win on lavapipe
    AccumulatePipeline(VulkanDevice& dev, const ContextConfig& config, bool interop, uint32_t sets, VkPipelineCache cache = VK_NULL_HANDLE);
    ~AccumulatePipeline();
    AccumulatePipeline(const AccumulatePipeline&) = delete;
    AccumulatePipeline& operator=(const AccumulatePipeline&) = delete;

    // sets: how many descriptor sets the pool holds (2 standalone: the
    // ping-pong parity; interop: 2 x frames in flight).
    VkDescriptorSet allocate_set();
    void write_set(VkDescriptorSet set, const DescriptorViews& views) const;
    void record(VkCommandBuffer cmd, VkDescriptorSet set, const FramePushConstants& pc, uint32_t width, uint32_t height) const;

private:
    void release();
    VulkanDevice& dev_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkSampler sampler_ = VK_NULL_HANDLE;  // nearest, clamp: texelFetch ignores it, the layout needs one
};

}  // namespace rrc
