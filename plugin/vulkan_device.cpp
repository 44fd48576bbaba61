#include "vulkan_device.h"

#include "error.h"
#include "vk_requirements.h"

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <vector>

namespace rrc {
namespace {

// volk's loader globals (vkGetInstanceProcAddr, vkCreateInstance, ...) are
// process-wide and identical for every instance: load them once.
// vkGetDeviceProcAddr, read by volkLoadDeviceTable, is set from the first
// instance: the loader's trampoline serves every device.
std::mutex g_volk_mutex;
bool g_volk_ready = false;

void load_loader() {
    std::lock_guard<std::mutex> lock(g_volk_mutex);
    if (g_volk_ready) return;
    if (volkInitialize() != VK_SUCCESS)
        fail(RRC_ERROR_DEVICE,
             "the Vulkan loader (libvulkan.so.1) could not be loaded: install libvulkan1 and a driver "
             "(mesa-vulkan-drivers provides lavapipe)");
    g_volk_ready = true;
}

const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool has_layer(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

bool has_instance_extension(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> exts(n);
    vkEnumerateInstanceExtensionProperties(nullptr, &n, exts.data());
    for (auto& e : exts)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

int device_rank(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

}  // namespace

void VulkanDevice::check(VkResult r, const char* what) {
    if (r == VK_SUCCESS) return;
    if (r == VK_ERROR_OUT_OF_HOST_MEMORY || r == VK_ERROR_OUT_OF_DEVICE_MEMORY)
        fail(RRC_ERROR_OUT_OF_MEMORY, "%s failed: out of memory (VkResult %d)", what, (int)r);
    if (r == VK_ERROR_DEVICE_LOST) fail(RRC_ERROR_DEVICE_LOST, "%s failed: device lost", what);
    fail(RRC_ERROR_DEVICE, "%s failed (VkResult %d)", what, (int)r);
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanDevice::on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                                        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* m = static_cast<Messages*>(user);
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        m->count.fetch_add(1);
        m->log(RRC_LOG_VALIDATION, data && data->pMessage ? data->pMessage : "(validation message without text)");
    }
    return VK_FALSE;
}

VulkanDevice::VulkanDevice(const std::string& device_filter, bool validation, Log log) : messages_(new Messages) {
    messages_->log = log;
    load_loader();
    try {
        create_instance(validation);
        std::string filter = device_filter;
        if (filter.empty())
            if (const char* env = std::getenv("RRC_DEVICE")) filter = env;
        pick_physical_device(filter);
        create_device();
    } catch (...) {
        release();  // the destructor does not run for a constructor that throws
        throw;
    }
}

void VulkanDevice::create_instance(bool validation) {
    std::vector<const char*> layers, extensions;
    if (validation) {
        if (!has_layer(kValidationLayer))
            fail(RRC_ERROR_UNSUPPORTED, "validation requested but %s is not installed (Debian: vulkan-validationlayers)", kValidationLayer);
        layers.push_back(kValidationLayer);
    }
    bool debug_utils = has_instance_extension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (validation && !debug_utils) fail(RRC_ERROR_UNSUPPORTED, "validation requested but VK_EXT_debug_utils is unavailable");
    if (debug_utils && validation) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pEngineName = "rrc";
    app.apiVersion = VK_API_VERSION_1_1;

    // Synchronization validation on top of the default checks.
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    // Also chained into instance creation so create/destroy messages are caught.
    VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    mci.pfnUserCallback = &VulkanDevice::on_message;
    mci.pUserData = messages_.get();
    features.pNext = &mci;

    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pNext = validation ? &features : nullptr;
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = (uint32_t)layers.size();
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = (uint32_t)extensions.size();
    ci.ppEnabledExtensionNames = extensions.data();
    check(vkCreateInstance(&ci, nullptr, &instance_), "vkCreateInstance");

    load_instance_functions(vkGetInstanceProcAddr, validation);
    {
        std::lock_guard<std::mutex> lock(g_volk_mutex);
        if (!vkGetDeviceProcAddr) vkGetDeviceProcAddr = (PFN_vkGetDeviceProcAddr)vkGetInstanceProcAddr(instance_, "vkGetDeviceProcAddr");
    }
    if (validation) check(fi.CreateDebugUtilsMessengerEXT(instance_, &mci, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
}

void VulkanDevice::load_instance_functions(PFN_vkGetInstanceProcAddr gipa, bool debug_utils) {
#define RRC_LOAD(name) fi.name = (PFN_vk##name)gipa(instance_, "vk" #name)
    RRC_LOAD(DestroyInstance);
    RRC_LOAD(EnumeratePhysicalDevices);
    RRC_LOAD(GetPhysicalDeviceProperties);
    RRC_LOAD(GetPhysicalDeviceFeatures);
    RRC_LOAD(GetPhysicalDeviceQueueFamilyProperties);
    RRC_LOAD(GetPhysicalDeviceMemoryProperties);
    RRC_LOAD(GetPhysicalDeviceFormatProperties);
    RRC_LOAD(GetPhysicalDeviceImageFormatProperties);
    RRC_LOAD(CreateDevice);
    if (debug_utils) {
        RRC_LOAD(CreateDebugUtilsMessengerEXT);
        RRC_LOAD(DestroyDebugUtilsMessengerEXT);
        RRC_LOAD(CmdBeginDebugUtilsLabelEXT);
        RRC_LOAD(CmdEndDebugUtilsLabelEXT);
    }
#undef RRC_LOAD
    if (!fi.GetPhysicalDeviceProperties || !fi.GetPhysicalDeviceMemoryProperties)
        fail(RRC_ERROR_DEVICE, "vkGetInstanceProcAddr returned no core instance functions");
}

VulkanDevice::VulkanDevice(const HostDevice& host, Log log) : messages_(new Messages), owns_(false) {
    messages_->log = log;
    instance_ = host.instance;
    physical = host.physical;
    device = host.device;
    queue_family = host.queue_family;
    allocator = host.allocator;
    load_instance_functions(host.get_instance_proc_addr, host.debug_utils);
    PFN_vkGetDeviceProcAddr gdpa = host.get_device_proc_addr;
    if (!gdpa) gdpa = (PFN_vkGetDeviceProcAddr)host.get_instance_proc_addr(instance_, "vkGetDeviceProcAddr");
    if (!gdpa) fail(RRC_ERROR_DEVICE, "no vkGetDeviceProcAddr from the host's vkGetInstanceProcAddr");
    {
        // volkLoadDeviceTable reads volk's global vkGetDeviceProcAddr: point it at
        // the host's loader for this call only, so the table holds the host's entry points.
        std::lock_guard<std::mutex> lock(g_volk_mutex);
        PFN_vkGetDeviceProcAddr saved = vkGetDeviceProcAddr;
        vkGetDeviceProcAddr = gdpa;
        volkLoadDeviceTable(&vk, device);
        vkGetDeviceProcAddr = saved;
    }
    VkPhysicalDeviceProperties p;
    fi.GetPhysicalDeviceProperties(physical, &p);
    name = p.deviceName;
    fi.GetPhysicalDeviceMemoryProperties(physical, &memory);
    check_physical_device();
}

void VulkanDevice::pick_physical_device(const std::string& filter) {
    uint32_t n = 0;
    check(fi.EnumeratePhysicalDevices(instance_, &n, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(n);
    check(fi.EnumeratePhysicalDevices(instance_, &n, devices.data()), "vkEnumeratePhysicalDevices");
    int best_rank = 1 << 30;
    std::string seen;
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceProperties p;
        fi.GetPhysicalDeviceProperties(d, &p);
        seen += std::string(seen.empty() ? "" : ", ") + p.deviceName;
        if (p.apiVersion < VK_API_VERSION_1_1) continue;
        if (!filter.empty() && std::strstr(p.deviceName, filter.c_str()) == nullptr) continue;
        int rank = filter.empty() ? device_rank(p.deviceType) : 0;
        if (rank < best_rank) {
            best_rank = rank;
            physical = d;
            name = p.deviceName;
        }
    }
    if (!physical) {
        if (filter.empty()) fail(RRC_ERROR_DEVICE, "no Vulkan 1.1 device found (install mesa-vulkan-drivers for lavapipe)");
        fail(RRC_ERROR_DEVICE, "no Vulkan 1.1 device name contains \"%s\" (devices: %s)", filter.c_str(), seen.c_str());
    }
    fi.GetPhysicalDeviceMemoryProperties(physical, &memory);
    check_physical_device();
}

void VulkanDevice::check_physical_device() {
    VkPhysicalDeviceFeatures f;
    fi.GetPhysicalDeviceFeatures(physical, &f);
    VkPhysicalDeviceProperties p;
    fi.GetPhysicalDeviceProperties(physical, &p);
    limits = p.limits;
    check_physical_device_requirements(p, f, [&](VkFormat fmt) {
        VkFormatProperties fp;
        fi.GetPhysicalDeviceFormatProperties(physical, fmt, &fp);
        return (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0;
    });
}

void VulkanDevice::create_device() {
    uint32_t n = 0;
    fi.GetPhysicalDeviceQueueFamilyProperties(physical, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    fi.GetPhysicalDeviceQueueFamilyProperties(physical, &n, families.data());
    bool found = false;
    for (uint32_t i = 0; i < n && !found; ++i)
        if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) queue_family = i, found = true;
    if (!found) fail(RRC_ERROR_DEVICE, "device \"%s\" has no compute queue", name.c_str());

    float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = queue_family;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    const VkPhysicalDeviceFeatures enabled = device_requirements().features;
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.pEnabledFeatures = &enabled;
    check(fi.CreateDevice(physical, &dci, nullptr, &device), "vkCreateDevice");
    {
        std::lock_guard<std::mutex> lock(g_volk_mutex);
        volkLoadDeviceTable(&vk, device);
    }
    vk.vkGetDeviceQueue(device, queue_family, 0, &queue);
}

VulkanDevice::~VulkanDevice() { release(); }

void VulkanDevice::release() {
    if (!owns_) return;  // the host's objects
    if (device) vk.vkDestroyDevice(device, nullptr);
    device = VK_NULL_HANDLE;
    if (messenger_) fi.DestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
    if (instance_) fi.DestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
}

}  // namespace rrc
