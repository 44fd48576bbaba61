// A scene frame's inputs (support/scene_frames.h) as the host's images, as
// the interop tests hand them over (include/rrc/rrc_vulkan.h): the depth, the
// PREV_CLIP reprojection, the 1- and 4-component samples and, when asked for,
// the 4-component channel's confidence; and zeroed output images.
#pragma once

#include "interop/vulkan_host.h"
#include "support/scene_frames.h"

namespace rrc_test {

struct SceneImages {
    HostImage depth, clip, s1, s4, conf;
    bool confidence = false;

    // storage: every input a storage image in the kernel's formats
    // (rrc_vulkan_frame_desc.storage_inputs, the depth R32); otherwise
    // sampled, the depth a depth attachment.
    SceneImages(VulkanHost& host, int W, int H, bool with_confidence, bool storage = false) : confidence(with_confidence) {
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
    void upload(VulkanHost& host, const SceneFrameInputs& in, VkImageLayout depth_layout, VkImageLayout layout) {
        const size_t n = (size_t)in.frame.width * in.frame.height;
        host.upload(depth, in.frame.depth.data(), n * 4, depth_layout);
        host.upload(clip, in.reprojection.data(), n * 16, layout);
        host.upload(s1, in.frame.signal1.data(), n * 4, layout);
        host.upload(s4, in.frame.signal4.data(), n * 16, layout);
        if (confidence) host.upload(conf, in.confidence[1].data(), n * 4, layout);
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

}  // namespace rrc_test
