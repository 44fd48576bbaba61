// A scene frame's inputs (support/scene_frames.h) as the host's images, as
// the interop tests hand them over (include/rrc/rrc_vulkan.h): the depth, the
// PREV_CLIP reprojection, the 1- and 4-component samples and, when asked for,
// the 4-component channel's confidence; zeroed output images; the frame and
// channel descriptions over them; the interop context on the host's device.
#pragma once

#include "interop/vulkan_host.h"
#include "support/scene_frames.h"

#include <rrc/rrc_vulkan.h>

#include "rrc_interop.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

namespace rrc_test {

// An interop context on the host's device `dd` (rrc_host::vulkan_device_desc);
// null, with a test failure naming the error, where it is refused.
inline rrc_context* interop_context(const rrc_vulkan_device_desc& dd, const rrc_context_desc& cd) {
    rrc_context* ctx = nullptr;
    const rrc_result r = rrc_vulkan_context_create(&cd, &dd, &ctx);
    EXPECT_EQ(r, RRC_SUCCESS) << rrc_last_error();
    return r == RRC_SUCCESS ? ctx : nullptr;
}

inline rrc_vulkan_image view_of(const HostImage& img, VkImageLayout layout) { return rrc_host::vulkan_image(img, layout); }

// An output image the kernel wrote (in GENERAL), read back as T's.
template <typename T>
std::vector<T> read_back(VulkanHost& host, HostImage& img) {
    const std::vector<unsigned char> bytes = host.download(img, VK_IMAGE_LAYOUT_GENERAL);
    std::vector<T> v(bytes.size() / sizeof(T));
    std::memcpy(v.data(), bytes.data(), bytes.size());
    return v;
}

struct SceneImages {
    HostImage depth, clip, s1, s4, conf;
    bool confidence = false, storage = false;
    // Where the last upload left them.
    VkImageLayout depth_layout = VK_IMAGE_LAYOUT_UNDEFINED, layout = VK_IMAGE_LAYOUT_UNDEFINED;

    // storage: every input a storage image in the kernel's formats
    // (rrc_vulkan_frame_desc.storage_inputs, the depth R32); otherwise
    // sampled, the depth a depth attachment.
    SceneImages(VulkanHost& host, int W, int H, bool with_confidence, bool storage_inputs = false)
        : confidence(with_confidence), storage(storage_inputs) {
        const VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT;
        const VkImageUsageFlags usage = sampled | (storage ? VK_IMAGE_USAGE_STORAGE_BIT : 0);
        depth = storage ? host.create_image(VK_FORMAT_R32_SFLOAT, W, H, usage)
                        : host.create_image(VK_FORMAT_D32_SFLOAT, W, H, sampled | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
        clip = host.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, W, H, usage);
        s1 = host.create_image(VK_FORMAT_R32_SFLOAT, W, H, usage);
        s4 = host.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, W, H, usage);
        if (confidence) conf = host.create_image(VK_FORMAT_R32_SFLOAT, W, H, usage);
    }

    // Frame `in` into the images, the depth left in depth_layout, the rest in `layout`.
    void upload(VulkanHost& host, const SceneFrameInputs& in, VkImageLayout depth_in, VkImageLayout rest_in) {
        const size_t n = (size_t)in.frame.width * in.frame.height;
        depth_layout = depth_in;
        layout = rest_in;
        host.upload(depth, in.frame.depth.data(), n * 4, depth_layout);
        host.upload(clip, in.reprojection.data(), n * 16, layout);
        host.upload(s1, in.frame.signal1.data(), n * 4, layout);
        host.upload(s4, in.frame.signal4.data(), n * 16, layout);
        if (confidence) host.upload(conf, in.confidence[1].data(), n * 4, layout);
    }

    // The 1- or 4-component channel's images: these samples (and the
    // 4-component one's confidence, when there is one) as uploaded, `output`
    // and, when given, `age` in GENERAL.
    rrc_vulkan_channel_images channel(int components, const HostImage& output, const HostImage* age = nullptr) const {
        auto c = rrc_host::rrc_struct<rrc_vulkan_channel_images>(RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES);
        c.samples = view_of(components == 1 ? s1 : s4, layout);
        if (components == 4 && confidence) c.confidence = view_of(conf, layout);
        c.output = view_of(output, VK_IMAGE_LAYOUT_GENERAL);
        if (age) c.age = view_of(*age, VK_IMAGE_LAYOUT_GENERAL);
        return c;
    }

    // The frame description of `in` (its index and jitter) over these images
    // as uploaded and the channels' images `ch`, recorded into `cmd`; the
    // caller adds what else the frame names (mask, statistics, ...).
    template <size_t N>
    rrc_vulkan_frame_desc frame(const SceneFrameInputs& in, const rrc_vulkan_channel_images (&ch)[N], VkCommandBuffer cmd) const {
        auto f = rrc_host::rrc_struct<rrc_vulkan_frame_desc>(RRC_STRUCT_TYPE_VULKAN_FRAME_DESC);
        f.frame_index = in.desc.frame_index;
        f.depth = view_of(depth, depth_layout);
        f.reprojection = view_of(clip, layout);
        f.storage_inputs = storage ? 1u : 0u;
        std::memcpy(f.jitter, in.desc.jitter, sizeof f.jitter);
        std::memcpy(f.prev_jitter, in.desc.prev_jitter, sizeof f.prev_jitter);
        f.channel_count = (uint32_t)N;
        f.channels = ch;
        f.command_buffer = cmd;
        return f;
    }

    void destroy(VulkanHost& host) {
        for (HostImage* img : {&depth, &clip, &s1, &s4}) host.destroy(*img);
        if (confidence) host.destroy(conf);
    }
};

// A storage image of `format`, zeroed and left in GENERAL: an output the kernel writes.
inline HostImage zeroed_output(VulkanHost& host, VkFormat format, int W, int H) {
    HostImage img = host.create_image(format, W, H, VK_IMAGE_USAGE_STORAGE_BIT);
    const std::vector<unsigned char> zeros((size_t)W * H * img.texel_bytes, 0);
    host.upload(img, zeros.data(), zeros.size(), VK_IMAGE_LAYOUT_GENERAL);
    return img;
}

// One frame in flight's images: its inputs and zeroed outputs for a 1- and
// a 4-component channel (values and ages) and the mask.
struct FrameImages {
    SceneImages in;
    HostImage out1, out4, mask, age1, age4;

    FrameImages(VulkanHost& host, int W, int H, bool with_confidence)
        : in(host, W, H, with_confidence),
          out1(zeroed_output(host, VK_FORMAT_R32_SFLOAT, W, H)),
          out4(zeroed_output(host, VK_FORMAT_R32G32B32A32_SFLOAT, W, H)),
          mask(zeroed_output(host, VK_FORMAT_R8_UINT, W, H)),
          age1(zeroed_output(host, VK_FORMAT_R16_UINT, W, H)),
          age4(zeroed_output(host, VK_FORMAT_R16_UINT, W, H)) {}

    // The 1- or 4-component channel's images, its age included.
    rrc_vulkan_channel_images channel(int components) const {
        return components == 1 ? in.channel(1, out1, &age1) : in.channel(4, out4, &age4);
    }

    void destroy(VulkanHost& host) {
        in.destroy(host);
        for (HostImage* img : {&out1, &out4, &mask, &age1, &age4}) host.destroy(*img);
    }
};

}  // namespace rrc_test
