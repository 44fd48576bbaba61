#include "gpu_resources.h"

#include "error.h"

#include <utility>

namespace rrc {
namespace {

uint32_t find_memory(const VulkanDevice& dev, uint32_t type_bits, VkMemoryPropertyFlags want) {
    for (uint32_t i = 0; i < dev.memory.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (dev.memory.memoryTypes[i].propertyFlags & want) == want) return i;
    fail(RRC_ERROR_OUT_OF_MEMORY, "no Vulkan memory type with properties 0x%x", (unsigned)want);
}

// One allocation of the given properties for an image's or a buffer's requirements.
VkDeviceMemory allocate(const VulkanDevice& dev, const VkMemoryRequirements& req, VkMemoryPropertyFlags want, const char* what) {
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = find_memory(dev, req.memoryTypeBits, want);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VulkanDevice::check(dev.vk.vkAllocateMemory(dev.device, &ai, dev.allocator, &memory), what);
    return memory;
}

}  // namespace

uint32_t texel_bytes(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8_UINT: return 1;
        case VK_FORMAT_R16_UINT:
        case VK_FORMAT_R16_SFLOAT: return 2;
        case VK_FORMAT_R32_UINT:
        case VK_FORMAT_R16G16_SFLOAT:
        case VK_FORMAT_R32_SFLOAT: return 4;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT: return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
        default: fail(RRC_ERROR_UNSUPPORTED, "internal: unexpected VkFormat %d", (int)format);
    }
}

GpuImage::GpuImage(VulkanDevice& dev, VkFormat fmt, uint32_t w, uint32_t h, VkFormat alias)
    : format(fmt), width(w), height(h), texel_bytes(rrc::texel_bytes(fmt)), dev_(&dev) {
    if (alias != VK_FORMAT_UNDEFINED && rrc::texel_bytes(alias) != texel_bytes)
        fail(RRC_ERROR_UNSUPPORTED, "internal: VkFormat %d cannot alias VkFormat %d", (int)alias, (int)fmt);
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    if (alias != VK_FORMAT_UNDEFINED) ci.flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = fmt;
    ci.extent = {w, h, 1};
    ci.mipLevels = 1;
    ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    // An image beyond what the device can hold is refused before it is made
    // (creating it anyway is invalid usage, not just a failed allocation).
    VkImageFormatProperties limits{};
    VulkanDevice::check(dev.fi.GetPhysicalDeviceImageFormatProperties(dev.physical, fmt, ci.imageType, ci.tiling, ci.usage, ci.flags, &limits),
                        "vkGetPhysicalDeviceImageFormatProperties");
    if (w > limits.maxExtent.width || h > limits.maxExtent.height || (VkDeviceSize)bytes() > limits.maxResourceSize)
        fail(RRC_ERROR_OUT_OF_MEMORY,
             "a %ux%u image of VkFormat %d needs %zu bytes: beyond this device's largest image (%ux%u, %llu bytes of memory)", w, h,
             (int)fmt, bytes(), limits.maxExtent.width, limits.maxExtent.height, (unsigned long long)limits.maxResourceSize);
    try {
        VulkanDevice::check(dev.vk.vkCreateImage(dev.device, &ci, dev.allocator, &image), "vkCreateImage");
        VkMemoryRequirements req;
        dev.vk.vkGetImageMemoryRequirements(dev.device, image, &req);
        memory_ = allocate(dev, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "vkAllocateMemory (image)");
        VulkanDevice::check(dev.vk.vkBindImageMemory(dev.device, image, memory_, 0), "vkBindImageMemory");
        VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vi.image = image;
        vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vi.format = fmt;
        vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VulkanDevice::check(dev.vk.vkCreateImageView(dev.device, &vi, dev.allocator, &view), "vkCreateImageView");
        if (alias != VK_FORMAT_UNDEFINED) {
            vi.format = alias;
            VulkanDevice::check(dev.vk.vkCreateImageView(dev.device, &vi, dev.allocator, &alias_view), "vkCreateImageView");
        }
    } catch (...) {
        reset();
        throw;
    }
}

void GpuImage::take(GpuImage& o) noexcept {
    std::swap(image, o.image), std::swap(view, o.view), std::swap(alias_view, o.alias_view), std::swap(memory_, o.memory_),
        std::swap(dev_, o.dev_);
    format = o.format, width = o.width, height = o.height, texel_bytes = o.texel_bytes;
}

void GpuImage::reset() {
    if (!dev_) return;
    if (view) dev_->vk.vkDestroyImageView(dev_->device, view, dev_->allocator);
    if (alias_view) dev_->vk.vkDestroyImageView(dev_->device, alias_view, dev_->allocator);
    if (image) dev_->vk.vkDestroyImage(dev_->device, image, dev_->allocator);
    if (memory_) dev_->vk.vkFreeMemory(dev_->device, memory_, dev_->allocator);
    view = alias_view = VK_NULL_HANDLE, image = VK_NULL_HANDLE, memory_ = VK_NULL_HANDLE;
}

HostBuffer::HostBuffer(VulkanDevice& dev, size_t bytes, VkBufferUsageFlags usage, bool device_local) : size(bytes), dev_(&dev) {
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = bytes;
    ci.usage = usage;
    try {
        VulkanDevice::check(dev.vk.vkCreateBuffer(dev.device, &ci, dev.allocator, &buffer), "vkCreateBuffer");
        VkMemoryRequirements req;
        dev.vk.vkGetBufferMemoryRequirements(dev.device, buffer, &req);
        memory_ = device_local ? allocate(dev, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "vkAllocateMemory (buffer)")
                               : allocate(dev, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                                          "vkAllocateMemory (staging)");
        VulkanDevice::check(dev.vk.vkBindBufferMemory(dev.device, buffer, memory_, 0), "vkBindBufferMemory");
        if (device_local) return;
        void* p = nullptr;
        VulkanDevice::check(dev.vk.vkMapMemory(dev.device, memory_, 0, VK_WHOLE_SIZE, 0, &p), "vkMapMemory");
        data = static_cast<unsigned char*>(p);
    } catch (...) {
        reset();
        throw;
    }
}

void HostBuffer::take(HostBuffer& o) noexcept {
    std::swap(buffer, o.buffer), std::swap(memory_, o.memory_), std::swap(dev_, o.dev_), std::swap(data, o.data);
    size = o.size;
}

void HostBuffer::reset() {
    if (!dev_) return;
    if (buffer) dev_->vk.vkDestroyBuffer(dev_->device, buffer, dev_->allocator);
    if (memory_) dev_->vk.vkFreeMemory(dev_->device, memory_, dev_->allocator);  // unmaps
    buffer = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    data = nullptr;
}

}  // namespace rrc

namespace rrc {

void record_initialise(const VulkanDevice& dev, VkCommandBuffer cmd, const std::vector<GpuImage*>& images) {
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    std::vector<VkImageMemoryBarrier> barriers;
    for (GpuImage* img : images) {
        if (!img->image) continue;
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = img->image;
        b.subresourceRange = range;
        barriers.push_back(b);
    }
    auto& vk = dev.vk;
    vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                            (uint32_t)barriers.size(), barriers.data());
    VkClearColorValue zero{};
    for (GpuImage* img : images)
        if (img->image) vk.vkCmdClearColorImage(cmd, img->image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                            1, &mb, 0, nullptr, 0, nullptr);
}

}  // namespace rrc
