// The standalone path's own Vulkan instance, device and queue.  Entry points
// come from volk: a per-device VolkDeviceTable (never volk's globals for
// device calls), so two contexts on two devices never mix.
#pragma once

#include "log.h"

#include <volk.h>

#include <atomic>
#include <memory>
#include <string>

namespace rrc {

struct InstanceFunctions {
    PFN_vkDestroyInstance DestroyInstance;
    PFN_vkEnumeratePhysicalDevices EnumeratePhysicalDevices;
    PFN_vkGetPhysicalDeviceProperties GetPhysicalDeviceProperties;
    PFN_vkGetPhysicalDeviceFeatures GetPhysicalDeviceFeatures;
    PFN_vkGetPhysicalDeviceQueueFamilyProperties GetPhysicalDeviceQueueFamilyProperties;
    PFN_vkGetPhysicalDeviceMemoryProperties GetPhysicalDeviceMemoryProperties;
    PFN_vkGetPhysicalDeviceFormatProperties GetPhysicalDeviceFormatProperties;
    PFN_vkCreateDevice CreateDevice;
    PFN_vkCreateDebugUtilsMessengerEXT CreateDebugUtilsMessengerEXT;
    PFN_vkDestroyDebugUtilsMessengerEXT DestroyDebugUtilsMessengerEXT;
};

class VulkanDevice {
public:
    // device_filter: empty = automatic (discrete > integrated > virtual > CPU),
    // else the first device whose name contains it.  Throws rrc::Error.
    VulkanDevice(const std::string& device_filter, bool validation, Log log);
    ~VulkanDevice();
    VulkanDevice(const VulkanDevice&) = delete;
    VulkanDevice& operator=(const VulkanDevice&) = delete;

    VolkDeviceTable vk{};
    VkDevice device = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkPhysicalDeviceMemoryProperties memory{};
    std::string name;
    uint64_t validation_messages() const { return messages_->count.load(); }

    // Throws the matching rrc::Error for a failed VkResult.
    static void check(VkResult result, const char* what);

private:
    struct Messages {  // outlives nothing: owned here, referenced by the messenger
        std::atomic<uint64_t> count{0};
        Log log;
    };
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT*, void*);
    void create_instance(bool validation);
    void pick_physical_device(const std::string& filter);
    void create_device();
    void release();

    std::unique_ptr<Messages> messages_;
    VkInstance instance_ = VK_NULL_HANDLE;
    InstanceFunctions fi_{};
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

}  // namespace rrc
