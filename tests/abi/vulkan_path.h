// The Vulkan path of the struct-size and bad-input tests: a host device
// (rrc_test::VulkanHost, validation on), an rrc context on it, the host images
// one frame needs, and a count of every command the library records, so a
// refused rrc_vulkan_record_frame can be shown to have recorded nothing.
//
// Counting: the device description hands the library our own
// get_instance_proc_addr / get_device_proc_addr, which return, for each
// vkCmd* below, a wrapper that counts the call and forwards to the real
// entry point (the library loads its device table through them).
#pragma once

#include "interop/vulkan_host.h"

#include <rrc/rrc.h>
#include <rrc/rrc_vulkan.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <vector>

namespace rrc_test {
namespace vkpath {

inline std::atomic<uint64_t>& recorded_commands() {
    static std::atomic<uint64_t> n{0};
    return n;
}

template <typename PFN, int Id>
struct Counted;
template <typename R, typename... A, int Id>
struct Counted<R (*)(A...), Id> {
    static inline PFN_vkVoidFunction real = nullptr;
    static R call(A... a) {
        ++recorded_commands();
        return reinterpret_cast<R (*)(A...)>(real)(a...);
    }
};

template <typename PFN, int Id>
PFN_vkVoidFunction install(PFN_vkVoidFunction real) {
    Counted<PFN, Id>::real = real;
    return reinterpret_cast<PFN_vkVoidFunction>(&Counted<PFN, Id>::call);
}

// Every command the library could record (those it uses today and the
// likely ones: copies, fills, clears, queries, labels, sync2 barriers).
#define RRC_TEST_COUNTED_COMMANDS(X)                                                                                                       \
    X(vkCmdPipelineBarrier)                                                                                                                \
    X(vkCmdPipelineBarrier2) X(vkCmdPipelineBarrier2KHR) X(vkCmdBindPipeline) X(vkCmdBindDescriptorSets) X(vkCmdPushConstants)             \
        X(vkCmdPushDescriptorSetKHR) X(vkCmdDispatch) X(vkCmdDispatchBase) X(vkCmdDispatchIndirect) X(vkCmdClearColorImage)                \
            X(vkCmdClearDepthStencilImage) X(vkCmdCopyBuffer) X(vkCmdCopyImage) X(vkCmdCopyBufferToImage) X(vkCmdCopyImageToBuffer)        \
                X(vkCmdBlitImage) X(vkCmdFillBuffer) X(vkCmdUpdateBuffer) X(vkCmdResetQueryPool) X(vkCmdWriteTimestamp) X(vkCmdBeginQuery) \
                    X(vkCmdEndQuery) X(vkCmdCopyQueryPoolResults) X(vkCmdSetEvent) X(vkCmdResetEvent) X(vkCmdWaitEvents)                   \
                        X(vkCmdExecuteCommands) X(vkCmdBeginDebugUtilsLabelEXT) X(vkCmdEndDebugUtilsLabelEXT)                              \
                            X(vkCmdInsertDebugUtilsLabelEXT)

inline PFN_vkVoidFunction wrap(const char* name, PFN_vkVoidFunction real) {
    if (!real) return nullptr;
#define RRC_TEST_WRAP(fn) \
    if (std::strcmp(name, #fn) == 0) return install<PFN_##fn, __COUNTER__>(real);
    RRC_TEST_COUNTED_COMMANDS(RRC_TEST_WRAP)
#undef RRC_TEST_WRAP
    return real;
}

inline PFN_vkVoidFunction VKAPI_PTR counting_device_proc_addr(VkDevice device, const char* name) {
    return wrap(name, vkGetDeviceProcAddr(device, name));
}

inline PFN_vkVoidFunction VKAPI_PTR counting_instance_proc_addr(VkInstance instance, const char* name) {
    if (std::strcmp(name, "vkGetDeviceProcAddr") == 0) return reinterpret_cast<PFN_vkVoidFunction>(&counting_device_proc_addr);
    return wrap(name, vkGetInstanceProcAddr(instance, name));
}

inline rrc_vulkan_device_desc device_desc(const VulkanHost& host) {
    rrc_vulkan_device_desc d;
    std::memset(&d, 0, sizeof d);
    d.type = RRC_STRUCT_TYPE_VULKAN_DEVICE_DESC;
    d.size = sizeof d;
    d.instance = host.instance;
    d.physical_device = host.physical;
    d.device = host.device;
    d.queue_family_index = host.family;
    d.vulkan_api_version = VK_API_VERSION_1_1;
    d.get_instance_proc_addr = &counting_instance_proc_addr;
    d.get_device_proc_addr = &counting_device_proc_addr;
    d.max_frames_in_flight = 2;
    d.debug_utils_enabled = host.debug_utils ? 1u : 0u;
    return d;
}

inline rrc_vulkan_image view_of(const HostImage& img, VkImageLayout layout) {
    rrc_vulkan_image v;
    std::memset(&v, 0, sizeof v);
    v.image = img.image;
    v.view = img.view;
    v.format = img.format;
    v.layout = layout;
    return v;
}

constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
constexpr VkImageLayout kDepthRead = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
constexpr VkImageLayout kGeneral = VK_IMAGE_LAYOUT_GENERAL;

// One frame's description with its channel images (desc.channels points
// into `channels`; re-pointed by VulkanRig::record).
struct VkFrame {
    rrc_vulkan_frame_desc desc;
    std::vector<rrc_vulkan_channel_images> channels;
};

// A context on `host` with every image its configuration reads or writes:
// depth (depth_format: D32_SFLOAT or D16_UNORM), reprojection (PREV_CLIP and
// MOTION_DEPTH: RGBA32F, MOTION: RG32F, CAMERA: none), do-not-cache mask
// (R8_UINT) if the context uses one, the R8_UINT mask, and per channel
// samples, confidence (if any), output (R32F or RGBA32F), age (R16_UINT) and
// a host-visible stats buffer.
class VulkanRig {
public:
    VulkanRig(VulkanHost& host, const rrc_context_desc& desc, VkFormat depth_format = VK_FORMAT_D32_SFLOAT)
        : host_(host), desc_(desc), channels_(desc.channels, desc.channels + desc.channel_count) {
        desc_.channels = channels_.data();
        const uint32_t w = desc.width, h = desc.height;
        const VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT, storage = VK_IMAGE_USAGE_STORAGE_BIT;
        depth = host.create_image(depth_format, w, h, sampled | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
        if (desc.reprojection == RRC_REPROJECTION_MOTION)
            reprojection = host.create_image(VK_FORMAT_R32G32_SFLOAT, w, h, sampled);
        else if (desc.reprojection != RRC_REPROJECTION_CAMERA)
            reprojection = host.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, w, h, sampled);
        if (desc.use_nocache_mask) nocache = host.create_image(VK_FORMAT_R8_UINT, w, h, sampled);
        if (desc.size > offsetof(rrc_context_desc, use_object_id) && desc.use_object_id)
            object_id = host.create_image(VK_FORMAT_R32_UINT, w, h, sampled);
        mask = host.create_image(VK_FORMAT_R8_UINT, w, h, storage);
        for (const rrc_channel_desc& c : channels_) {
            const VkFormat f = c.components == 4 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R32_SFLOAT;
            Images im;
            im.samples = host.create_image(f, w, h, sampled);
            if (c.confidence) im.confidence = host.create_image(VK_FORMAT_R32_SFLOAT, w, h, sampled);
            im.output = host.create_image(f, w, h, storage);
            static_cast<rrc_host::Image&>(im.age) = host.rrc_host::VulkanBootstrap::create_image(
                VK_FORMAT_R16_UINT, w, h, storage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
            im.age.texel_bytes = 2;
            images.push_back(im);
        }
        stats = host.create_buffer(512, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        rrc_vulkan_device_desc dd = device_desc(host);
        create_result = rrc_vulkan_context_create(&desc_, &dd, &ctx);
    }
    ~VulkanRig() {
        rrc_context_destroy(ctx);
        for (HostImage* img : {&depth, &reprojection, &nocache, &object_id, &mask})
            if (img->image) host_.destroy(*img);
        for (Images& im : images)
            for (HostImage* img : {&im.samples, &im.confidence, &im.output, &im.age})
                if (img->image) host_.destroy(*img);
        host_.rrc_host::VulkanBootstrap::destroy(stats);
    }
    VulkanRig(const VulkanRig&) = delete;
    VulkanRig& operator=(const VulkanRig&) = delete;

    struct Images {
        HostImage samples, confidence, output, age;
    };
    rrc_context* ctx = nullptr;
    rrc_result create_result = RRC_SUCCESS;
    HostImage depth, reprojection, nocache, object_id, mask;
    std::vector<Images> images;
    rrc_host::Buffer stats;
    static constexpr VkDeviceSize kStatsOffset = 256;

    size_t pixels() const { return (size_t)desc_.width * desc_.height; }
    const rrc_context_desc& desc() const { return desc_; }

    void upload_depth(const std::vector<float>& d) {
        if (depth.format == VK_FORMAT_D16_UNORM) {
            std::vector<uint16_t> u(d.size());
            for (size_t i = 0; i < d.size(); ++i) u[i] = (uint16_t)(std::min(std::max(d[i], 0.0f), 1.0f) * 65535.0f + 0.5f);
            host_.upload(depth, u.data(), u.size() * 2, kDepthRead);
        } else {
            host_.upload(depth, d.data(), d.size() * 4, kDepthRead);
        }
    }
    // PREV_CLIP/MOTION_DEPTH: 4 floats a pixel (MOTION_DEPTH uses 3), MOTION: 2.
    void upload_reprojection(const std::vector<float>& r) { host_.upload(reprojection, r.data(), r.size() * 4, kRead); }
    void upload_nocache(const std::vector<uint8_t>& m) { host_.upload(nocache, m.data(), m.size(), kRead); }
    void upload_object_id(const std::vector<uint32_t>& ids) { host_.upload(object_id, ids.data(), ids.size() * 4, kRead); }
    void upload_samples(uint32_t c, const std::vector<float>& s) { host_.upload(images[c].samples, s.data(), s.size() * 4, kRead); }
    void upload_confidence(uint32_t c, const std::vector<float>& s) { host_.upload(images[c].confidence, s.data(), s.size() * 4, kRead); }
    // Fills every output (values, age, mask, stats) with sentinels.
    void fill_outputs(float value = -7.0f, uint16_t age = 777, uint8_t mask_value = 0xEE) {
        for (uint32_t c = 0; c < images.size(); ++c) {
            std::vector<float> v(pixels() * channels_[c].components, value);
            host_.upload(images[c].output, v.data(), v.size() * 4, kGeneral);
            std::vector<uint16_t> a(pixels(), age);
            host_.upload(images[c].age, a.data(), a.size() * 2, kGeneral);
        }
        std::vector<uint8_t> m(pixels(), mask_value);
        host_.upload(mask, m.data(), m.size(), kGeneral);
        std::memset(stats.mapped, 0xEE, (size_t)stats.size);
    }

    // A good frame naming every image (ages, mask and stats included).
    VkFrame frame(uint64_t index = 0) const {
        VkFrame f;
        std::memset(&f.desc, 0, sizeof f.desc);
        f.desc.type = RRC_STRUCT_TYPE_VULKAN_FRAME_DESC;
        f.desc.size = sizeof f.desc;
        f.desc.frame_index = index;
        f.desc.depth = view_of(depth, kDepthRead);
        if (reprojection.image) f.desc.reprojection = view_of(reprojection, kRead);
        if (nocache.image) f.desc.nocache = view_of(nocache, kRead);
        if (object_id.image) f.desc.object_id = view_of(object_id, kRead);
        f.desc.mask = view_of(mask, kGeneral);
        f.desc.stats_buffer = stats.buffer;
        f.desc.stats_offset = kStatsOffset;
        if (desc_.reprojection == RRC_REPROJECTION_CAMERA) {
            for (int i = 0; i < 16; i += 5) f.desc.view_proj[i] = f.desc.prev_view_proj[i] = 1.0;
        }
        for (uint32_t c = 0; c < images.size(); ++c) {
            rrc_vulkan_channel_images ci;
            std::memset(&ci, 0, sizeof ci);
            ci.type = RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES;
            ci.size = sizeof ci;
            ci.samples = view_of(images[c].samples, kRead);
            if (images[c].confidence.image) ci.confidence = view_of(images[c].confidence, kRead);
            ci.output = view_of(images[c].output, kGeneral);
            ci.age = view_of(images[c].age, kGeneral);
            f.channels.push_back(ci);
        }
        f.desc.channel_count = (uint32_t)f.channels.size();
        return f;
    }

    // Records `f` into a fresh command buffer (spoil runs after the command
    // buffer and channel pointer are set), then submits it and waits, whatever
    // the result.  *recorded: the commands the library recorded.
    rrc_result record(VkFrame& f, const std::function<void(VkFrame&)>& spoil = {}, uint64_t* recorded = nullptr) {
        VkCommandBuffer cmd = host_.begin();
        f.desc.command_buffer = cmd;
        f.desc.channels = f.channels.data();
        if (spoil) spoil(f);
        const uint64_t before = recorded_commands();
        const rrc_result r = rrc_vulkan_record_frame(ctx, &f.desc);
        if (recorded) *recorded = recorded_commands() - before;
        host_.submit_and_wait(cmd);
        return r;
    }

    std::vector<float> values(uint32_t c) {
        std::vector<unsigned char> b = host_.download(images[c].output, kGeneral);
        std::vector<float> v(b.size() / 4);
        std::memcpy(v.data(), b.data(), b.size());
        return v;
    }
    std::vector<uint16_t> age(uint32_t c) {
        std::vector<unsigned char> b = host_.rrc_host::VulkanBootstrap::download(images[c].age, pixels() * 2, kGeneral);
        std::vector<uint16_t> v(pixels());
        std::memcpy(v.data(), b.data(), b.size());
        return v;
    }
    std::vector<uint8_t> mask_bytes() {
        std::vector<unsigned char> b = host_.download(mask, kGeneral);
        return std::vector<uint8_t>(b.begin(), b.end());
    }
    rrc_vulkan_frame_stats frame_stats() const {
        rrc_vulkan_frame_stats s;
        std::memcpy(&s, (const char*)stats.mapped + kStatsOffset, sizeof s);
        return s;
    }
    // The stats buffer's bytes outside [kStatsOffset, +sizeof stats) (must stay as filled).
    bool stats_guard_untouched(unsigned char fill = 0xEE) const {
        const unsigned char* b = (const unsigned char*)stats.mapped;
        for (size_t i = 0; i < (size_t)stats.size; ++i)
            if ((i < kStatsOffset || i >= kStatsOffset + sizeof(rrc_vulkan_frame_stats)) && b[i] != fill) return false;
        return true;
    }

private:
    VulkanHost& host_;
    rrc_context_desc desc_;
    std::vector<rrc_channel_desc> channels_;
};

}  // namespace vkpath
}  // namespace rrc_test
