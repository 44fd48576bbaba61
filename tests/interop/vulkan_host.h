// A minimal Vulkan "engine" for tests: its own instance (validation layer with
// synchronization validation, every message counted), device, queue and
// command pool, and helpers to make images and move float data in and out.
// It plays the host of the interop API.
#pragma once

#include <volk.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rrc_test {

struct HostImage {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0, texel_bytes = 0;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
};

class VulkanHost {
public:
    VulkanHost();  // throws std::runtime_error
    ~VulkanHost() { shutdown(); }
    // Destroys device and instance; messages emitted meanwhile (leaks) are kept.
    void shutdown();

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t family = 0;
    std::vector<std::string> messages;  // validation messages (warnings and errors)

    // usage: VK_IMAGE_USAGE_* (TRANSFER_SRC/DST are always added).
    HostImage create_image(VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage);
    void destroy(HostImage& image);
    // Uploads raw texel bytes and leaves the image in `layout`.
    void upload(HostImage& image, const void* data, size_t bytes, VkImageLayout layout);
    // Reads raw texel bytes of an image that is in `layout` (left there).
    std::vector<unsigned char> download(HostImage& image, VkImageLayout layout);
    // A one-time command buffer: begin, then submit_and_wait it.
    VkCommandBuffer begin();
    void submit_and_wait(VkCommandBuffer cmd);
    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const;

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT*, void*);
    void transition(VkCommandBuffer cmd, HostImage& img, VkImageLayout from, VkImageLayout to);
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
};

}  // namespace rrc_test
