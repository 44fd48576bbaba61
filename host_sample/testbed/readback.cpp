#include "readback.h"

#include <stdexcept>

namespace rrc_sample {

uint32_t texel_bytes(VkFormat f) {
    switch (f) {
        case VK_FORMAT_R8_UINT: return 1;
        case VK_FORMAT_R16_UINT: return 2;
        case VK_FORMAT_R32_SFLOAT:
        case VK_FORMAT_R8G8B8A8_UNORM: return 4;
        case VK_FORMAT_R16G16B16A16_SFLOAT: return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
        default: throw std::runtime_error("readback: unsupported format");
    }
}

int Readback::add(const Image& image, VkImageLayout layout) {
    const VkDeviceSize bytes = (VkDeviceSize)image.width * image.height * texel_bytes(image.format);
    slots_.push_back({&image, total_, bytes, layout});
    total_ += (bytes + 15) & ~VkDeviceSize(15);
    return (int)slots_.size() - 1;
}

void Readback::allocate() { buffer_ = gpu_.create_buffer(total_, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, "readback"); }

void Readback::record(VkCommandBuffer cmd, const std::vector<int>& slots) const {
    // -> TRANSFER_SRC_OPTIMAL for the copies (earlier writes of any stage made visible, earlier reads done), then back.
    std::vector<VkImageMemoryBarrier> to_src, to_general;
    for (int s : slots) {
        const Slot& slot = slots_.at(s);
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = slot.image->image;
        b.subresourceRange = {slot.image->aspect, 0, 1, 0, 1};
        b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
        b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        b.oldLayout = slot.layout;
        b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        to_src.push_back(b);
        b.srcAccessMask = 0;  // reads only: an execution dependency orders the transition after them
        b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        b.newLayout = slot.layout;
        to_general.push_back(b);
    }
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                         (uint32_t)to_src.size(), to_src.data());
    for (int s : slots) {
        const Slot& slot = slots_.at(s);
        VkBufferImageCopy r{};
        r.bufferOffset = slot.offset;
        r.imageSubresource = {slot.image->aspect, 0, 0, 1};
        r.imageExtent = {slot.image->width, slot.image->height, 1};
        vkCmdCopyImageToBuffer(cmd, slot.image->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer_.buffer, 1, &r);
    }
    VkMemoryBarrier host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &host,
                         0, nullptr, (uint32_t)to_general.size(), to_general.data());
}

}  // namespace rrc_sample
