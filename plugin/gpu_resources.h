// Images and buffers owned by the library: RAII over a VulkanDevice, one
// allocation each (a context holds a few dozen at most).
#pragma once

#include "vulkan_device.h"

#include <vector>

namespace rrc {

class GpuImage {
public:
    GpuImage() = default;
    // A 2D storage image in GENERAL layout once initialised (see Context).
    GpuImage(VulkanDevice& dev, VkFormat format, uint32_t width, uint32_t height);
    ~GpuImage() { reset(); }
    GpuImage(GpuImage&& o) noexcept { *this = std::move(o); }
    GpuImage& operator=(GpuImage&& o) noexcept;

    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0;
    uint32_t texel_bytes = 0;
    size_t bytes() const { return (size_t)width * height * texel_bytes; }

private:
    void reset();
    VulkanDevice* dev_ = nullptr;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
};

// Host-visible, coherent, persistently mapped: staging for uploads and readbacks.
class HostBuffer {
public:
    HostBuffer() = default;
    HostBuffer(VulkanDevice& dev, size_t bytes, VkBufferUsageFlags usage);
    ~HostBuffer() { reset(); }
    HostBuffer(HostBuffer&& o) noexcept { *this = std::move(o); }
    HostBuffer& operator=(HostBuffer&& o) noexcept;

    VkBuffer buffer = VK_NULL_HANDLE;
    unsigned char* data = nullptr;
    size_t size = 0;

private:
    void reset();
    VulkanDevice* dev_ = nullptr;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
};

uint32_t texel_bytes(VkFormat format);

// Records the one-time start of the library's images: UNDEFINED -> GENERAL
// (the only layout the library uses for its own images), cleared to zero so
// even a never-written texel reads as zero, visible to later copies and kernels.
void record_initialise(const VulkanDevice& dev, VkCommandBuffer cmd, const std::vector<GpuImage*>& images);

}  // namespace rrc
