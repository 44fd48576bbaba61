// A minimal Vulkan "engine" for tests: it plays the host of the interop API.
// Instance (validation layer with synchronization validation, every message
// counted), device choice (RRC_DEVICE honoured), queue, command pool and the
// image and staging helpers are the bootstrap rrc-sample uses too
// (host_sample/common/vulkan_bootstrap.h); this adds texel sizes, so tests can
// move float data in and out by image alone.
#pragma once

#include "vulkan_bootstrap.h"

namespace rrc_test {

struct HostImage : rrc_host::Image {
    uint32_t texel_bytes = 0;
};

class VulkanHost : public rrc_host::VulkanBootstrap {
public:
    VulkanHost();  // throws std::runtime_error; validation is always on

    // usage: VK_IMAGE_USAGE_* (TRANSFER_SRC/DST are always added).
    HostImage create_image(VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage);
    void destroy(HostImage& image);
    // Uploads raw texel bytes and leaves the image in `layout`.
    void upload(HostImage& image, const void* data, size_t bytes, VkImageLayout layout);
    // Reads raw texel bytes of an image that is in `layout` (left there).
    std::vector<unsigned char> download(HostImage& image, VkImageLayout layout);
};

}  // namespace rrc_test
