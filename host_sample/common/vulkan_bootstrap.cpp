// The bootstrap's instance, device choice and validation messages
// (vulkan_bootstrap.h says why there is one bootstrap); the resource helpers
// are in vulkan_resources.cpp.
#include "vulkan_bootstrap.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace rrc_host {

void vk_check(VkResult r, const char* what) {
    if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string((int)r) + ")");
}

namespace {

const char* const kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr size_t kKeptMessages = 32;

// Vulkan's two-call enumeration: `query(count, nullptr)`, then `query(count, data)`.
template <typename T, typename Query>
std::vector<T> enumerate(Query query) {
    uint32_t n = 0;
    query(&n, nullptr);
    std::vector<T> items(n);
    query(&n, items.data());
    items.resize(n);
    return items;
}

bool layer_present(const char* name) {
    for (const VkLayerProperties& l : enumerate<VkLayerProperties>(vkEnumerateInstanceLayerProperties))
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

bool instance_extension_present(const char* name) {
    auto all = enumerate<VkExtensionProperties>(
        [](uint32_t* n, VkExtensionProperties* p) { return vkEnumerateInstanceExtensionProperties(nullptr, n, p); });
    for (const VkExtensionProperties& e : all)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

// Lower is preferred: discrete > integrated > virtual > CPU (lavapipe) > other.
int preference(VkPhysicalDeviceType type) {
    static const VkPhysicalDeviceType order[] = {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU,
                                                 VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU, VK_PHYSICAL_DEVICE_TYPE_CPU};
    int i = 0;
    while (i < 4 && order[i] != type) ++i;
    return i;
}

// The explicit name wins, then RRC_DEVICE (as for rrc's own device, include/rrc/rrc.h).
std::string wanted_device(const std::string& explicit_name) {
    if (!explicit_name.empty()) return explicit_name;
    const char* env = std::getenv("RRC_DEVICE");
    return env ? std::string(env) : std::string();
}

struct Candidate {
    VkPhysicalDevice device = VK_NULL_HANDLE;
    int family = -1;  // a family with graphics and compute
    uint32_t timestamp_bits = 0;
    int preference = 1 << 30;
};

// Every feature `wanted` sets, `has` sets too (VkPhysicalDeviceFeatures is an array of VkBool32).
bool has_features(const VkPhysicalDeviceFeatures& has, const VkPhysicalDeviceFeatures& wanted) {
    const VkBool32* h = &has.robustBufferAccess;
    const VkBool32* w = &wanted.robustBufferAccess;
    for (size_t i = 0; i < sizeof(VkPhysicalDeviceFeatures) / sizeof(VkBool32); ++i)
        if (w[i] && !h[i]) return false;
    return true;
}

Candidate examine(VkPhysicalDevice pd, const VkPhysicalDeviceFeatures& wanted) {
    Candidate c;
    c.device = pd;
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    VkPhysicalDeviceFeatures f;
    vkGetPhysicalDeviceFeatures(pd, &f);
    if (p.apiVersion < VK_API_VERSION_1_1 || !has_features(f, wanted)) return c;
    auto families = enumerate<VkQueueFamilyProperties>(
        [pd](uint32_t* n, VkQueueFamilyProperties* q) { vkGetPhysicalDeviceQueueFamilyProperties(pd, n, q); });
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (size_t i = 0; i < families.size() && c.family < 0; ++i)
        if ((families[i].queueFlags & need) == need) {
            c.family = (int)i;
            c.timestamp_bits = families[i].timestampValidBits;
            c.preference = preference(p.deviceType);
        }
    return c;
}

}  // namespace

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanBootstrap::on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                                           const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
    auto* self = static_cast<VulkanBootstrap*>(user);
    std::lock_guard<std::mutex> lock(self->mutex_);
    ++self->count_;
    if (self->messages_.size() < kKeptMessages) self->messages_.push_back(data && data->pMessage ? data->pMessage : "(no text)");
    return VK_FALSE;
}

uint64_t VulkanBootstrap::message_count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
}

std::vector<std::string> VulkanBootstrap::messages() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
}

VulkanBootstrap::VulkanBootstrap(const BootstrapOptions& options) {
    try {
        create_instance(options);
        enabled_features = options.features;
        choose_physical_device(wanted_device(options.device_name));
        create_device();
    } catch (...) {
        shutdown();  // the destructor does not run for a constructor that throws
        throw;
    }
}

void VulkanBootstrap::create_instance(const BootstrapOptions& options) {
    vk_check(volkInitialize(), "volkInitialize (is libvulkan1 installed?)");
    validation = options.validation;
    if (validation && !layer_present(kValidationLayer))
        throw std::runtime_error(std::string("validation: ") + kValidationLayer + " is not installed (Debian: vulkan-validationlayers)");
    debug_utils = instance_extension_present(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (validation && !debug_utils) throw std::runtime_error("validation needs VK_EXT_debug_utils");

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = options.application.c_str();
    app.pEngineName = options.application.c_str();
    app.apiVersion = api_version;

    // The messenger is also chained into vkCreateInstance, so messages of
    // instance creation and destruction are counted too.
    const VkDebugUtilsMessengerCreateInfoEXT messenger{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        nullptr,
        0,
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        &VulkanBootstrap::on_message,
        this};
    const VkValidationFeatureEnableEXT sync_validation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, &messenger, 1, &sync_validation};

    const char* layer = kValidationLayer;
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pNext = validation ? &features : nullptr;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = validation ? 1 : 0;
    info.ppEnabledLayerNames = &layer;
    info.enabledExtensionCount = debug_utils ? 1 : 0;
    info.ppEnabledExtensionNames = &extension;
    vk_check(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
    volkLoadInstanceOnly(instance);
    if (validation) vk_check(vkCreateDebugUtilsMessengerEXT(instance, &messenger, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
}

void VulkanBootstrap::choose_physical_device(const std::string& wanted) {
    auto devices =
        enumerate<VkPhysicalDevice>([this](uint32_t* n, VkPhysicalDevice* d) { return vkEnumeratePhysicalDevices(instance, n, d); });
    Candidate best;
    for (VkPhysicalDevice pd : devices) {
        Candidate c = examine(pd, enabled_features);
        if (c.family < 0) continue;
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        if (!wanted.empty() && std::string(p.deviceName).find(wanted) == std::string::npos) continue;
        if (c.preference < best.preference) best = c;
    }
    if (best.family < 0)
        throw std::runtime_error(wanted.empty() ? "no Vulkan 1.1 device with graphics+compute and the features asked for (rrc_vulkan_get_requirements)"
                                                : "no suitable Vulkan device whose name contains \"" + wanted + "\"");
    physical = best.device;
    family = (uint32_t)best.family;
    vkGetPhysicalDeviceProperties(physical, &properties);
    timestamps = best.timestamp_bits > 0 && properties.limits.timestampPeriod > 0.0f;
}

void VulkanBootstrap::create_device() {
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue_info;
    info.pEnabledFeatures = &enabled_features;
    vk_check(vkCreateDevice(physical, &info, nullptr, &device), "vkCreateDevice");
    volkLoadDevice(device);
    vkGetDeviceQueue(device, family, 0, &queue);
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = family;
    vk_check(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
}

void VulkanBootstrap::shutdown() {
    if (device) {
        vkDeviceWaitIdle(device);
        if (pool) vkDestroyCommandPool(device, pool, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (messenger_) vkDestroyDebugUtilsMessengerEXT(instance, messenger_, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
    pool = VK_NULL_HANDLE;
    device = VK_NULL_HANDLE;
    messenger_ = VK_NULL_HANDLE;
    instance = VK_NULL_HANDLE;
}

}  // namespace rrc_host
