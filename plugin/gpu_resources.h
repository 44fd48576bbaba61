// Images and buffers owned by the library: RAII over a VulkanDevice, one
// allocation each (a context holds a few dozen at most).
#pragma once

#include "vulkan_device.h"

#include <vector>

namespace rrc {

// The move-only RAII members both resource types share: destroyed with
// their owner; a move releases ours (reset) and takes theirs (take, which
// leaves the source empty).
#define RRC_MOVE_ONLY_RESOURCE(T)         \
    ~T() { reset(); }                     \
    T(T&& o) noexcept { take(o); }        \
    T& operator=(T&& o) noexcept {        \
        if (this != &o) reset(), take(o); \
        return *this;                     \
    }                                     \
    T(const T&) = delete;                 \
    T& operator=(const T&) = delete;

class GpuImage {
public:
    GpuImage() = default;
    // A 2D storage image; record_initialise (below) moves it to GENERAL, cleared.
    // `alias`, a format of the same texel size: the image is created
    // MUTABLE_FORMAT and alias_view reads its texels as that format.
    GpuImage(VulkanDevice& dev, VkFormat format, uint32_t width, uint32_t height, VkFormat alias = VK_FORMAT_UNDEFINED);
    RRC_MOVE_ONLY_RESOURCE(GpuImage)

    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkImageView alias_view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0;
    uint32_t texel_bytes = 0;
    size_t bytes() const { return (size_t)width * height * texel_bytes; }

private:
    void reset();
    void take(GpuImage& o) noexcept;  // o's handles and description; o keeps ours (none after reset)
    VulkanDevice* dev_ = nullptr;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
};

// Host-visible, coherent, persistently mapped: staging for uploads and
// readbacks.  `device_local`: a buffer only kernels touch (the fill list):
// device-local memory, not mapped (data stays NULL).
class HostBuffer {
public:
    HostBuffer() = default;
    HostBuffer(VulkanDevice& dev, size_t bytes, VkBufferUsageFlags usage, bool device_local = false);
    RRC_MOVE_ONLY_RESOURCE(HostBuffer)

    VkBuffer buffer = VK_NULL_HANDLE;
    unsigned char* data = nullptr;
    size_t size = 0;

private:
    void reset();
    void take(HostBuffer& o) noexcept;
    VulkanDevice* dev_ = nullptr;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
};

uint32_t texel_bytes(VkFormat format);

// Records the one-time start of the library's images: UNDEFINED -> GENERAL
// (the only layout the library uses for its own images), cleared to zero so
// even a never-written texel reads as zero, visible to later copies and kernels.
void record_initialise(const VulkanDevice& dev, VkCommandBuffer cmd, const std::vector<GpuImage*>& images);

}  // namespace rrc
