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
    PFN_vkGetPhysicalDeviceImageFormatProperties GetPhysicalDeviceImageFormatProperties;
    PFN_vkCreateDevice CreateDevice;
    PFN_vkCreateDebugUtilsMessengerEXT CreateDebugUtilsMessengerEXT;
    PFN_vkDestroyDebugUtilsMessengerEXT DestroyDebugUtilsMessengerEXT;
    PFN_vkCmdBeginDebugUtilsLabelEXT CmdBeginDebugUtilsLabelEXT;  // NULL unless debug utils is enabled
    PFN_vkCmdEndDebugUtilsLabelEXT CmdEndDebugUtilsLabelEXT;
};

// The host's Vulkan objects (interop): used, never destroyed.
struct HostDevice {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
    PFN_vkGetDeviceProcAddr get_device_proc_addr = nullptr;  // optional
    const VkAllocationCallbacks* allocator = nullptr;
    bool debug_utils = false;  // the host enabled VK_EXT_debug_utils on its instance
};

class VulkanDevice {
public:
    // device_filter: empty = automatic (discrete > integrated > virtual > CPU),
    // else the first device whose name contains it.  Throws rrc::Error.
    VulkanDevice(const std::string& device_filter, bool validation, Log log);
    // Interop: wraps the host's device; entry points come from its loader.
    VulkanDevice(const HostDevice& host, Log log);
    ~VulkanDevice();
    VulkanDevice(const VulkanDevice&) = delete;
    VulkanDevice& operator=(const VulkanDevice&) = delete;

    VolkDeviceTable vk{};
    VkDevice device = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkPhysicalDeviceMemoryProperties memory{};
    VkPhysicalDeviceLimits limits{};
    const VkAllocationCallbacks* allocator = nullptr;  // the host's, or NULL
    InstanceFunctions fi{};
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

    void load_instance_functions(PFN_vkGetInstanceProcAddr gipa, bool debug_utils);
    void check_physical_device();

    std::unique_ptr<Messages> messages_;
    VkInstance instance_ = VK_NULL_HANDLE;
    bool owns_ = true;  // false: the host's objects
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

}  // namespace rrc
