// The sample's own Vulkan instance and device (the "engine" side of the
// interop API).  Instance, device choice (--device / RRC_DEVICE), validation
// messages and the image, buffer and one-time-command helpers come from the
// bootstrap shared with the interop tests (host_sample/common/vulkan_bootstrap.h);
// this adds what only the sample needs: shaders and storage-image setup.
#pragma once

#include "vulkan_bootstrap.h"

namespace rrc_sample {

using rrc_host::Buffer;
using rrc_host::Image;
using rrc_host::memory_barrier;
using rrc_host::vk_check;

/** Compute writes -> later compute reads and writes (storage images, read-modify-write chains). */
void compute_to_compute(VkCommandBuffer cmd);

/** A base for the passes and resources that own Vulkan objects: never copied. */
struct NonCopyable {
    NonCopyable() = default;
    NonCopyable(const NonCopyable&) = delete;
    NonCopyable& operator=(const NonCopyable&) = delete;
};

struct GpuOptions {
    bool validation = false;  // VK_LAYER_KHRONOS_validation + synchronization validation
    std::string device_name;  // substring of the device name; "" = RRC_DEVICE or discrete > integrated > any
};

class Gpu : public rrc_host::VulkanBootstrap {
public:
    explicit Gpu(const GpuOptions& options);  // throws std::runtime_error

    VkShaderModule create_shader(const uint32_t* code, size_t bytes);
    /** Moves storage images from UNDEFINED to GENERAL, cleared to zero (once, at creation). */
    void init_storage_images(const std::vector<Image*>& images);
};

}  // namespace rrc_sample
