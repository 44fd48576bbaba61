// The bootstrap's resource helpers: memory types, images, buffers, barriers,
// one-time command buffers and staging copies.  rrc-sample and the interop
// tests' host both need exactly these (vulkan_bootstrap.h says why they share).
#include "vulkan_bootstrap.h"

#include <cstring>
#include <stdexcept>

namespace rrc_host {
namespace {

bool is_depth(VkFormat f) { return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D16_UNORM; }

// Allocates memory of `flags` (falling back to `fallback` when no type has
// them) for requirements `req`.
VkDeviceMemory allocate(const VulkanBootstrap& vk, const VkMemoryRequirements& req, VkMemoryPropertyFlags flags,
                        VkMemoryPropertyFlags fallback) {
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    try {
        ai.memoryTypeIndex = vk.memory_type(req.memoryTypeBits, flags);
    } catch (const std::runtime_error&) {
        ai.memoryTypeIndex = vk.memory_type(req.memoryTypeBits, fallback);
    }
    VkDeviceMemory memory = VK_NULL_HANDLE;
    vk_check(vkAllocateMemory(vk.device, &ai, nullptr, &memory), "vkAllocateMemory");
    return memory;
}

VkBufferImageCopy whole_image(const Image& img) {
    VkBufferImageCopy r{};
    r.imageSubresource = {img.aspect, 0, 0, 1};
    r.imageExtent = {img.width, img.height, 1};
    return r;
}

// Staging copies run alone on the queue: a full barrier on each side is enough.
constexpr VkAccessFlags kAnyWrite = VK_ACCESS_MEMORY_WRITE_BIT;
constexpr VkAccessFlags kAnyAccess = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;

void relayout(VkCommandBuffer cmd, const Image& img, VkImageLayout from, VkImageLayout to) {
    image_barriers(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                   {layout_change(img, from, to, kAnyWrite, kAnyAccess)});
}

}  // namespace

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stages, VkAccessFlags src_access, VkPipelineStageFlags dst_stages,
                    VkAccessFlags dst_access) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = src_access;
    mb.dstAccessMask = dst_access;
    vkCmdPipelineBarrier(cmd, src_stages, dst_stages, 0, 1, &mb, 0, nullptr, 0, nullptr);
}

VkImageMemoryBarrier layout_change(const Image& image, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                                   VkAccessFlags dst_access) {
    return VkImageMemoryBarrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
                                nullptr,
                                src_access,
                                dst_access,
                                from,
                                to,
                                VK_QUEUE_FAMILY_IGNORED,
                                VK_QUEUE_FAMILY_IGNORED,
                                image.image,
                                {image.aspect, 0, 1, 0, 1}};
}

void image_barriers(VkCommandBuffer cmd, VkPipelineStageFlags src_stages, VkPipelineStageFlags dst_stages,
                    const std::vector<VkImageMemoryBarrier>& barriers) {
    vkCmdPipelineBarrier(cmd, src_stages, dst_stages, 0, 0, nullptr, 0, nullptr, (uint32_t)barriers.size(), barriers.data());
}

uint32_t VulkanBootstrap::memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(physical, &mp);
    for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw std::runtime_error("no Vulkan memory type with the needed properties");
}

void VulkanBootstrap::set_name(VkObjectType type, uint64_t handle, const char* name) {
    if (!debug_utils || !name || !vkSetDebugUtilsObjectNameEXT) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name;
    vkSetDebugUtilsObjectNameEXT(device, &info);
}

Image VulkanBootstrap::create_image(VkFormat format, uint32_t w, uint32_t h, VkImageUsageFlags usage, const char* name) {
    Image img;
    img.format = format;
    img.width = w;
    img.height = h;
    img.aspect = is_depth(format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = format;
    ci.extent = {w, h, 1};
    ci.mipLevels = ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = usage;
    vk_check(vkCreateImage(device, &ci, nullptr, &img.image), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, img.image, &req);
    img.memory = allocate(*this, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    vk_check(vkBindImageMemory(device, img.image, img.memory, 0), "vkBindImageMemory");
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = img.image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {img.aspect, 0, 1, 0, 1};
    vk_check(vkCreateImageView(device, &vi, nullptr, &img.view), "vkCreateImageView");
    set_name(VK_OBJECT_TYPE_IMAGE, (uint64_t)img.image, name);
    set_name(VK_OBJECT_TYPE_IMAGE_VIEW, (uint64_t)img.view, name);
    return img;
}

void VulkanBootstrap::destroy(Image& img) {
    if (img.view) vkDestroyImageView(device, img.view, nullptr);
    if (img.image) vkDestroyImage(device, img.image, nullptr);
    if (img.memory) vkFreeMemory(device, img.memory, nullptr);
    img = Image();
}

Buffer VulkanBootstrap::create_buffer(VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible, const char* name) {
    Buffer b;
    b.size = size;
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = size;
    bci.usage = usage;
    vk_check(vkCreateBuffer(device, &bci, nullptr, &b.buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, b.buffer, &req);
    // Host-visible: prefer cached memory (reads from uncached memory are slow on GPUs).
    const VkMemoryPropertyFlags mapped = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    b.memory = host_visible ? allocate(*this, req, mapped | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, mapped)
                            : allocate(*this, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    vk_check(vkBindBufferMemory(device, b.buffer, b.memory, 0), "vkBindBufferMemory");
    if (host_visible) vk_check(vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
    set_name(VK_OBJECT_TYPE_BUFFER, (uint64_t)b.buffer, name);
    return b;
}

void VulkanBootstrap::destroy(Buffer& b) {
    if (b.buffer) vkDestroyBuffer(device, b.buffer, nullptr);
    if (b.memory) vkFreeMemory(device, b.memory, nullptr);  // unmaps implicitly
    b = Buffer();
}

VkCommandBuffer VulkanBootstrap::begin() {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd;
    vk_check(vkAllocateCommandBuffers(device, &ai, &cmd), "vkAllocateCommandBuffers");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    return cmd;
}

void VulkanBootstrap::submit_and_wait(VkCommandBuffer cmd) {
    vk_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    vk_check(vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
    vk_check(vkQueueWaitIdle(queue), "vkQueueWaitIdle");
    vkFreeCommandBuffers(device, pool, 1, &cmd);
}

void VulkanBootstrap::immediate(const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBuffer cmd = begin();
    record(cmd);
    submit_and_wait(cmd);
}

void VulkanBootstrap::upload(const Image& img, const void* data, size_t bytes, VkImageLayout layout) {
    Buffer staging = create_buffer(bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, data, bytes);
    immediate([&](VkCommandBuffer cmd) {
        relayout(cmd, img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkBufferImageCopy r = whole_image(img);
        vkCmdCopyBufferToImage(cmd, staging.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
        relayout(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, layout);
    });
    destroy(staging);
}

std::vector<unsigned char> VulkanBootstrap::download(const Image& img, size_t bytes, VkImageLayout layout) {
    Buffer staging = create_buffer(bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    immediate([&](VkCommandBuffer cmd) {
        relayout(cmd, img, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        const VkBufferImageCopy r = whole_image(img);
        vkCmdCopyImageToBuffer(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &r);
        relayout(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout);
        memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                       VK_ACCESS_HOST_READ_BIT);
    });
    const unsigned char* p = static_cast<const unsigned char*>(staging.mapped);
    std::vector<unsigned char> out(p, p + bytes);
    destroy(staging);
    return out;
}

}  // namespace rrc_host
