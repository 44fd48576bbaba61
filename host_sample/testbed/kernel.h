// A compute pipeline with its own descriptor set layout and a few
// descriptor sets (one per binding variant, e.g. ping-pong images).
#pragma once

#include "gpu.h"

#include <vector>

namespace rrc_sample {

class ComputeKernel {
public:
    ComputeKernel() = default;
    /** bindings[i] is the descriptor type of binding i.  Workgroups are 128x1 (lavapipe's best: ~2% over 64x1, 8x8 ~1.45x slower). */
    ComputeKernel(Gpu& gpu, const char* name, const uint32_t* spirv, size_t bytes, std::vector<VkDescriptorType> bindings,
                  uint32_t push_bytes, uint32_t sets = 1);
    ~ComputeKernel() { release(); }
    ComputeKernel(ComputeKernel&& o) noexcept { *this = std::move(o); }
    ComputeKernel& operator=(ComputeKernel&& o) noexcept;
    ComputeKernel(const ComputeKernel&) = delete;
    ComputeKernel& operator=(const ComputeKernel&) = delete;
    void release();

    void bind_buffer(uint32_t set, uint32_t binding, VkBuffer buffer);
    /** A storage image (GENERAL) or a combined image sampler (nearest; `layout` as it is when sampled). */
    void bind_image(uint32_t set, uint32_t binding, VkImageView view, VkImageLayout layout);
    /** Binds set `set`, pushes constants, dispatches over width x height. */
    void dispatch(VkCommandBuffer cmd, uint32_t set, const void* push, uint32_t width, uint32_t height) const;
    /** The same with the group counts read from `buffer` at `offset` (a VkDispatchIndirectCommand). */
    void dispatch_indirect(VkCommandBuffer cmd, uint32_t set, const void* push, VkBuffer buffer, VkDeviceSize offset) const;

private:
    // One descriptor of `set`: a buffer or an image.
    void write(uint32_t set, uint32_t binding, const VkDescriptorBufferInfo* buffer, const VkDescriptorImageInfo* image);
    Gpu* gpu_ = nullptr;
    std::vector<VkDescriptorType> types_;
    uint32_t push_bytes_ = 0;
    VkSampler sampler_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    std::vector<VkDescriptorSet> sets_;
};

/** A nearest, clamp-to-edge sampler (texelFetch ignores it; combined samplers need one). */
VkSampler create_nearest_sampler(Gpu& gpu);

}  // namespace rrc_sample
