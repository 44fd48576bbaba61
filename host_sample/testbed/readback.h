// Copies of GPU images into one host-visible buffer at the end of a frame.
#pragma once

#include "gpu.h"

#include <vector>

namespace rrc_sample {

class Readback {
public:
    explicit Readback(Gpu& gpu) : gpu_(gpu) {}
    ~Readback() { gpu_.destroy(buffer_); }
    Readback(const Readback&) = delete;
    Readback& operator=(const Readback&) = delete;

    /** Registers an image that is in `layout` when copied (and is left in); returns its slot.  Call before allocate(). */
    int add(const Image& image, VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL);
    void allocate();
    /** Records the copies of `slots` (compute writes made visible first; host reads after). */
    void record(VkCommandBuffer cmd, const std::vector<int>& slots) const;
    /** The slot's texels after the frame's fence. */
    const void* data(int slot) const { return (const char*)buffer_.mapped + slots_.at(slot).offset; }
    size_t bytes(int slot) const { return slots_.at(slot).bytes; }

private:
    struct Slot {
        const Image* image;
        VkDeviceSize offset, bytes;
        VkImageLayout layout;
    };
    Gpu& gpu_;
    std::vector<Slot> slots_;
    VkDeviceSize total_ = 0;
    Buffer buffer_;
};

uint32_t texel_bytes(VkFormat format);

}  // namespace rrc_sample
