// The sample's own Vulkan instance and device (the "engine" side of the
// interop API): device choice, the optional Khronos validation layer with
// synchronization validation (every warning and error counted, teardown
// included), and helpers for images, buffers, shaders and one-time commands.
#pragma once

#include <volk.h>

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace rrc_sample {

/** Throws std::runtime_error naming `what` unless r is VK_SUCCESS. */
void vk_check(VkResult r, const char* what);

/** A global memory barrier. */
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stages, VkAccessFlags src_access, VkPipelineStageFlags dst_stages,
                    VkAccessFlags dst_access);
/** Compute writes -> later compute reads and writes (storage images, read-modify-write chains). */
void compute_to_compute(VkCommandBuffer cmd);

struct GpuOptions {
    bool validation = false;  // VK_LAYER_KHRONOS_validation + synchronization validation
    std::string device_name;  // substring of the device name; "" = RRC_DEVICE or discrete > integrated > any
};

struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
};

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;  // host-visible buffers stay mapped
};

class Gpu {
public:
    explicit Gpu(const GpuOptions& options);  // throws std::runtime_error
    ~Gpu() { shutdown(); }
    Gpu(const Gpu&) = delete;
    Gpu& operator=(const Gpu&) = delete;

    /** Destroys pool, device, messenger and instance (idempotent).  Messages
     *  the layer emits meanwhile (leaked objects) are still counted. */
    void shutdown();

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t family = 0;
    uint32_t api_version = VK_API_VERSION_1_1;
    VkPhysicalDeviceProperties properties{};
    bool debug_utils = false;  // VK_EXT_debug_utils enabled (object names, labels)
    bool timestamps = false;   // the queue family has valid timestamp bits
    bool validation = false;

    std::string device_name() const { return properties.deviceName; }
    uint64_t message_count() const;
    std::vector<std::string> messages() const;  // the first 32

    Image create_image(VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage, const char* name);
    void destroy(Image& image);
    Buffer create_buffer(VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible, const char* name);
    void destroy(Buffer& buffer);
    VkShaderModule create_shader(const uint32_t* code, size_t bytes);
    void set_name(VkObjectType type, uint64_t handle, const char* name);

    /** Moves storage images from UNDEFINED to GENERAL, cleared to zero (once, at creation). */
    void init_storage_images(const std::vector<Image*>& images);
    /** Records with `record` into a one-time command buffer, submits, waits. */
    void immediate(const std::function<void(VkCommandBuffer)>& record);
    VkCommandPool pool = VK_NULL_HANDLE;  // RESET_COMMAND_BUFFER

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT*, void*);
    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    mutable std::mutex mutex_;
    uint64_t count_ = 0;
    std::vector<std::string> messages_;
};

}  // namespace rrc_sample
