// The kernels' pipelines (compute/rrc_module_*.comp; a module runs one or more passes): descriptor layout, specialization constants
// chosen from the context's configuration (so a scene pays only for what it
// enables) and the dispatch.  Binding numbers, constant ids and push-constant
// offsets come from compute/rrc_kernel_interface.h, which the kernels read too.
#pragma once

#include "config.h"
#include "gpu_resources.h"
#include "vulkan_device.h"

#include <rrc_kernel_interface.h>
#include <rrc_module_bindings.h>

#include <cstddef>
#include <map>

namespace rrc {

// A descriptor binding: one of RRC_BINDING_* (compute/rrc_kernel_interface.h).
using Binding = uint32_t;
constexpr uint32_t kFirstChannelBinding = RRC_BINDING_FIRST_CHANNEL, kLastBinding = RRC_BINDING_LAST, kBindingCount = kLastBinding + 1;

// Sampled (combined image sampler) bindings; all others are storage images.
inline bool is_sampled_binding(uint32_t b) {
    return b == RRC_BINDING_HOST_DEPTH || b == RRC_BINDING_HOST_REPROJ || b == RRC_BINDING_HOST_NOCACHE || b == RRC_BINDING_HOST_SAMPLES ||
           b == RRC_BINDING_HOST_CONFIDENCE || b == RRC_BINDING_HOST_OBJECT_ID || b == RRC_BINDING_CLASSIFIED || b == RRC_BINDING_FALLBACK ||
           b == RRC_BINDING_GATE;
}
inline uint32_t binding_count(uint32_t b) {
    return (b >= kFirstChannelBinding && b <= RRC_BINDING_LAST_CHANNEL) || b == RRC_BINDING_FALLBACK || b == RRC_BINDING_GATE ? RRC_MAX_CHANNELS : 1;
}

// The image view bound at [binding][slot], for every binding of every module:
// each module's set takes the bindings of its list (compute/rrc_module_bindings.h),
// and each of those entries must be filled (placeholders where a
// configuration does not use a binding).
struct DescriptorViews {
    VkImageView view[kBindingCount][RRC_MAX_CHANNELS] = {};
    VkImageLayout layout[kBindingCount][RRC_MAX_CHANNELS] = {};  // 0 = GENERAL
    VkBuffer stats = VK_NULL_HANDLE;                             // RRC_BINDING_STATS: the host's buffer or a placeholder
    VkDeviceSize stats_offset = 0;
    VkDeviceSize stats_range = RRC_STAT_COUNT * sizeof(uint32_t);  // with the I/O counts, those words too
    VkBuffer quads = VK_NULL_HANDLE;  // RRC_BINDING_QUADS: classify's list (the host's, the library's, or a placeholder)
    VkDeviceSize quads_offset = 0, quads_range = VK_WHOLE_SIZE;
    VkBuffer fill_list = VK_NULL_HANDLE;  // RRC_BINDING_FILL_LIST: the library's
    VkBuffer view_buffer = VK_NULL_HANDLE;  // RRC_BINDING_VIEW: the library's (a placeholder without a view lobe)
};

// The module (RRC_MODULE_*) that runs a pass (RRC_PASS_*).
inline uint32_t module_of(uint32_t pass) {
    return pass == RRC_PASS_LIST ? RRC_MODULE_LIST : pass == RRC_PASS_COPY_OUT ? RRC_MODULE_COPY_OUT : pass == RRC_PASS_FILL ? RRC_MODULE_FILL : RRC_MODULE_FRAME;
}

// A binding of the library's descriptor sets: one set a module, each
// with its own layout, written from the same DescriptorViews.
struct DescriptorSets {
    VkDescriptorSet module[RRC_MODULE_COUNT] = {};
};

// What a frame asks of the kernel beyond the context's configuration: the
// optional interop outputs, and how it reads the host's inputs.  Each combination is its own specialised
// pipeline, made the first time a frame asks for it, so an output nobody
// asks for costs nothing.
struct KernelVariant {
    bool stats = false;
    bool count_io = false;  // with stats: the image loads and stores counted after them (rrc_vulkan_frame_desc.count_io)
    bool storage_inputs = false;  // the host's inputs bound to the storage bindings (rrc_vulkan_frame_desc.storage_inputs)
    uint32_t host_age_mask = 0;   // bit c: slot c writes the host's age image
    uint32_t pass = RRC_PASS_FUSED;  // RRC_PASS_*: the pass (plugin/frame_plan.cpp chooses)
    uint32_t host_out_mask = 0;   // bit c: slot c writes RRC_BINDING_HOST_OUT
    bool copy_mask = false;       // COPY_OUT: the classified mask into RRC_BINDING_MASK
    bool mask_in_place = false;   // LIST, RESOLVE, RESOLVE_LISTED: classify's mask is the image bound at RRC_BINDING_MASK
    uint32_t key() const {
        return (stats ? 1u : 0u) | (storage_inputs ? 2u : 0u) | host_age_mask << 2 | pass << 6 | host_out_mask << 9 | (copy_mask ? 1u : 0u) << 13 |
               (mask_in_place ? 1u : 0u) << 14 | (count_io ? 1u : 0u) << 15;
    }
};

// Layout of `Frame` in compute/rrc_reproject.glsl, whose members sit at the
// RRC_PC_OFFSET_* of compute/rrc_kernel_interface.h (asserted below).
struct FramePushConstants {
    float M[16];  // column-major
    float inv_row3[4];
    float jitter[4];
    float motion_scale[2];
    float eps;
    float near_plane, far_plane;
    float bg_threshold;
    uint32_t prev_valid;
    uint32_t refresh_phase;
};
static_assert(sizeof(FramePushConstants) == RRC_PC_SIZE, "must match the GLSL push-constant block");
static_assert(offsetof(FramePushConstants, M) == RRC_PC_OFFSET_M, "Frame.M");
static_assert(offsetof(FramePushConstants, inv_row3) == RRC_PC_OFFSET_INV_ROW3, "Frame.inv_row3");
static_assert(offsetof(FramePushConstants, jitter) == RRC_PC_OFFSET_JITTER, "Frame.jitter");
static_assert(offsetof(FramePushConstants, motion_scale) == RRC_PC_OFFSET_MOTION_SCALE, "Frame.motion_scale");
static_assert(offsetof(FramePushConstants, eps) == RRC_PC_OFFSET_EPS, "Frame.eps");
static_assert(offsetof(FramePushConstants, near_plane) == RRC_PC_OFFSET_NEAR_PLANE, "Frame.near_plane");
static_assert(offsetof(FramePushConstants, far_plane) == RRC_PC_OFFSET_FAR_PLANE, "Frame.far_plane");
static_assert(offsetof(FramePushConstants, bg_threshold) == RRC_PC_OFFSET_BG_THRESHOLD, "Frame.bg_threshold");
static_assert(offsetof(FramePushConstants, prev_valid) == RRC_PC_OFFSET_PREV_VALID, "Frame.prev_valid");
static_assert(offsetof(FramePushConstants, refresh_phase) == RRC_PC_OFFSET_REFRESH_PHASE, "Frame.refresh_phase");
static_assert(RRC_PC_SIZE <= 128, "push constants must fit Vulkan's guaranteed 128 bytes");

class AccumulatePipeline {
public:
    static constexpr uint32_t kGroupX = 128, kGroupY = 1;  // wide groups win on lavapipe (128x1 ~2% over 64x1; 8x8 is ~1.45x slower)
    // The indirect passes' groups: RESOLVE_LISTED runs two invocations a
    // listed quad, FILL one a listed pixel (compute/rrc_module_frame.comp, rrc_module_fill.comp).
    static_assert(2 * RRC_QUADS_PER_GROUP == kGroupX && RRC_FILL_LIST_PER_GROUP == kGroupX, "the lists' groups are the kernel's");
    AccumulatePipeline(VulkanDevice& dev, const ContextConfig& config, bool interop, uint32_t sets, VkPipelineCache cache = VK_NULL_HANDLE);
    ~AccumulatePipeline();
    AccumulatePipeline(const AccumulatePipeline&) = delete;
    AccumulatePipeline& operator=(const AccumulatePipeline&) = delete;

    // sets: how many DescriptorSets the pool holds (2 standalone: the
    // ping-pong parity; interop: 2 x frames in flight).
    DescriptorSets allocate_set();
    // Writes each module's set with the bindings of its list only.
    void write_set(const DescriptorSets& sets, const DescriptorViews& views) const;
    // A dispatch over width x height invocations (LIST: over its 2x2 quads).
    void record(VkCommandBuffer cmd, const DescriptorSets& sets, const FramePushConstants& pc, uint32_t width, uint32_t height,
                const KernelVariant& variant = {});
    // An indirect dispatch: the VkDispatchIndirectCommand at `offset` of `buffer`.
    void record_indirect(VkCommandBuffer cmd, const DescriptorSets& sets, const FramePushConstants& pc, const KernelVariant& variant,
                         VkBuffer buffer, VkDeviceSize offset);
    // Makes (once) and returns the variant's pipeline: call before recording
    // so that a failure leaves the command buffer untouched.
    VkPipeline pipeline(const KernelVariant& variant);

private:
    void release();
    // Binds the variant's pipeline, its module's set and the push constants.
    void bind(VkCommandBuffer cmd, const DescriptorSets& sets, const FramePushConstants& pc, const KernelVariant& variant);
    VulkanDevice& dev_;
    ContextConfig config_;
    bool interop_;
    VkPipelineCache cache_;
    VkDescriptorSetLayout set_layouts_[RRC_MODULE_COUNT] = {};  // by RRC_MODULE_*: its bindings only
    VkPipelineLayout layouts_[RRC_MODULE_COUNT] = {};
    std::map<uint32_t, VkPipeline> pipelines_;  // by KernelVariant::key()
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkSampler sampler_ = VK_NULL_HANDLE;  // nearest, clamp: texelFetch ignores it, the layout needs one
    HostBuffer params_;  // RRC_BINDING_CHANNEL_PARAMS: the channels' parameter block (plugin/channel_options.h)
};

}  // namespace rrc
