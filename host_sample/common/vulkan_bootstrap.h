// One Vulkan bootstrap for every program outside the library that plays the
// engine's part: rrc-sample (host_sample/testbed/gpu.h) and the interop
// tests' host (tests/interop/vulkan_host.h).  Both used to make their own
// instance, pick their own device (the tests took the first one and ignored
// RRC_DEVICE) and repeat the same image, buffer, staging and one-time-command
// code.  It is written once here, so a fix to device choice or to message
// counting reaches both.  Only Vulkan (through volk, VK_NO_PROTOTYPES) is
// used: rrc itself is reached through include/rrc/ by the callers, as
// docs/guide/integration.md describes.
#pragma once

#include <volk.h>

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace rrc_host {

/** Throws std::runtime_error naming `what` unless r is VK_SUCCESS. */
void vk_check(VkResult r, const char* what);

struct BootstrapOptions {
    std::string application = "rrc-host";
    bool validation = false;  // VK_LAYER_KHRONOS_validation + synchronization validation (throws if missing)
    std::string device_name;  // substring of the device name; "" = RRC_DEVICE, else discrete > integrated > any
    // The features to enable; a device that lacks one is passed over.  rrc's
    // come from rrc_vulkan_get_requirements (rrc_interop.h, rrc_features()).
    VkPhysicalDeviceFeatures features{};
};

/** A 2D image with one mip level and one layer, its memory and a view. */
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

/** A global memory barrier. */
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stages, VkAccessFlags src_access, VkPipelineStageFlags dst_stages,
                    VkAccessFlags dst_access);
/** The barrier that moves the whole of `image` from one layout to another
 *  (no queue family transfer); callers batch them into vkCmdPipelineBarrier. */
VkImageMemoryBarrier layout_change(const Image& image, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                                   VkAccessFlags dst_access);
/** Records one pipeline barrier made of image barriers only. */
void image_barriers(VkCommandBuffer cmd, VkPipelineStageFlags src_stages, VkPipelineStageFlags dst_stages,
                    const std::vector<VkImageMemoryBarrier>& barriers);

/** Instance (optional validation, every warning and error counted, those of
 *  vkCreateInstance and vkDestroyInstance included), physical device, one
 *  graphics+compute queue, a command pool, and resource helpers.  The device
 *  enables the options' features (what rrc needs: rrc_vulkan_get_requirements). */
class VulkanBootstrap {
public:
    explicit VulkanBootstrap(const BootstrapOptions& options);  // throws std::runtime_error
    virtual ~VulkanBootstrap() { shutdown(); }
    VulkanBootstrap(const VulkanBootstrap&) = delete;
    VulkanBootstrap& operator=(const VulkanBootstrap&) = delete;

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
    VkCommandPool pool = VK_NULL_HANDLE;  // RESET_COMMAND_BUFFER
    bool debug_utils = false;             // VK_EXT_debug_utils enabled (object names, labels)
    bool timestamps = false;              // the queue family has valid timestamp bits
    bool validation = false;
    VkPhysicalDeviceFeatures enabled_features{};  // what vkCreateDevice enabled (rrc_vulkan_device_desc.enabled_features)

    std::string device_name() const { return properties.deviceName; }
    uint64_t message_count() const;
    std::vector<std::string> messages() const;  // the first 32

    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const;
    void set_name(VkObjectType type, uint64_t handle, const char* name);

    Image create_image(VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage, const char* name = nullptr);
    void destroy(Image& image);
    /** host_visible: mapped, coherent, cached where the device offers it (readback). */
    Buffer create_buffer(VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible, const char* name = nullptr);
    void destroy(Buffer& buffer);

    /** A one-time command buffer: begin, then submit_and_wait it (which frees it). */
    VkCommandBuffer begin();
    void submit_and_wait(VkCommandBuffer cmd);
    /** Records with `record` into a one-time command buffer, submits, waits. */
    void immediate(const std::function<void(VkCommandBuffer)>& record);

    /** Copies `bytes` of tightly packed texels into `image` through a staging
     *  buffer; the old contents are dropped and the image is left in `layout`. */
    void upload(const Image& image, const void* data, size_t bytes, VkImageLayout layout);
    /** Reads `bytes` of tightly packed texels of an image that is in `layout` (left there). */
    std::vector<unsigned char> download(const Image& image, size_t bytes, VkImageLayout layout);

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT*, void*);
    void create_instance(const BootstrapOptions& options);
    void choose_physical_device(const std::string& wanted);
    void create_device();
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    mutable std::mutex mutex_;
    uint64_t count_ = 0;
    std::vector<std::string> messages_;
};

}  // namespace rrc_host
