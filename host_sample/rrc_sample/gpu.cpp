#include "gpu.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace rrc_sample {

void vk_check(VkResult r, const char* what) {
    if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string((int)r) + ")");
}

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stages, VkAccessFlags src_access, VkPipelineStageFlags dst_stages,
                    VkAccessFlags dst_access) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = src_access;
    mb.dstAccessMask = dst_access;
    vkCmdPipelineBarrier(cmd, src_stages, dst_stages, 0, 1, &mb, 0, nullptr, 0, nullptr);
}

void compute_to_compute(VkCommandBuffer cmd) {
    memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

namespace {

bool has_layer(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

bool has_instance_extension(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> exts(n);
    vkEnumerateInstanceExtensionProperties(nullptr, &n, exts.data());
    for (const auto& e : exts)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

int rank(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

// A queue family with graphics and compute (graphics families always allow
// compute-capable transfer); -1 if none.
int graphics_compute_family(VkPhysicalDevice pd, uint32_t* timestamp_bits) {
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
    for (uint32_t i = 0; i < n; ++i) {
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need) {
            *timestamp_bits = families[i].timestampValidBits;
            return (int)i;
        }
    }
    return -1;
}

}  // namespace

VKAPI_ATTR VkBool32 VKAPI_CALL Gpu::on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                               const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
    auto* gpu = static_cast<Gpu*>(user);
    std::lock_guard<std::mutex> lock(gpu->mutex_);
    ++gpu->count_;
    if (gpu->messages_.size() < 32) gpu->messages_.push_back(data && data->pMessage ? data->pMessage : "(no text)");
    return VK_FALSE;
}

uint64_t Gpu::message_count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
}

std::vector<std::string> Gpu::messages() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
}

Gpu::Gpu(const GpuOptions& options) {
    vk_check(volkInitialize(), "volkInitialize (is libvulkan1 installed?)");
    validation = options.validation;
    if (validation && !has_layer("VK_LAYER_KHRONOS_validation"))
        throw std::runtime_error("--validation: VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers)");
    debug_utils = has_instance_extension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (validation && !debug_utils) throw std::runtime_error("--validation needs VK_EXT_debug_utils");

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "rrc-sample";
    app.pEngineName = "rrc-sample";
    app.apiVersion = api_version;
    std::vector<const char*> layers, extensions;
    if (validation) layers.push_back("VK_LAYER_KHRONOS_validation");
    if (debug_utils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    mci.pfnUserCallback = &Gpu::on_message;
    mci.pUserData = this;
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    features.pNext = &mci;  // messages of vkCreateInstance/vkDestroyInstance too

    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pNext = validation ? (const void*)&features : nullptr;
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = (uint32_t)layers.size();
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = (uint32_t)extensions.size();
    ci.ppEnabledExtensionNames = extensions.data();
    vk_check(vkCreateInstance(&ci, nullptr, &instance), "vkCreateInstance");
    volkLoadInstanceOnly(instance);
    if (validation) vk_check(vkCreateDebugUtilsMessengerEXT(instance, &mci, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");

    // Device: --device / RRC_DEVICE substring, else discrete > integrated > virtual > CPU.
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(instance, &n, nullptr);
    std::vector<VkPhysicalDevice> devices(n);
    vkEnumeratePhysicalDevices(instance, &n, devices.data());
    std::string want = options.device_name;
    if (want.empty() && std::getenv("RRC_DEVICE")) want = std::getenv("RRC_DEVICE");
    int best = -1, best_rank = 1000;
    uint32_t best_family = 0, best_ts = 0;
    for (uint32_t i = 0; i < n; ++i) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        VkPhysicalDeviceFeatures f;
        vkGetPhysicalDeviceFeatures(devices[i], &f);
        uint32_t ts = 0;
        int fam = graphics_compute_family(devices[i], &ts);
        if (p.apiVersion < VK_API_VERSION_1_1 || fam < 0 || !f.shaderStorageImageWriteWithoutFormat) continue;
        if (!want.empty() && std::string(p.deviceName).find(want) == std::string::npos) continue;
        if (rank(p.deviceType) < best_rank) {
            best = (int)i;
            best_rank = rank(p.deviceType);
            best_family = (uint32_t)fam;
            best_ts = ts;
        }
    }
    if (best < 0)
        throw std::runtime_error(want.empty() ? "no Vulkan 1.1 device with graphics+compute and shaderStorageImageWriteWithoutFormat"
                                              : "no suitable Vulkan device whose name contains \"" + want + "\"");
    physical = devices[best];
    family = best_family;
    vkGetPhysicalDeviceProperties(physical, &properties);
    timestamps = best_ts > 0 && properties.limits.timestampPeriod > 0.0f;

    float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = family;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkPhysicalDeviceFeatures enabled{};
    enabled.shaderStorageImageWriteWithoutFormat = VK_TRUE;  // rrc's kernel writes any float output format
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.pEnabledFeatures = &enabled;
    vk_check(vkCreateDevice(physical, &dci, nullptr, &device), "vkCreateDevice");
    volkLoadDevice(device);
    vkGetDeviceQueue(device, family, 0, &queue);
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = family;
    vk_check(vkCreateCommandPool(device, &pci, nullptr, &pool), "vkCreateCommandPool");
}

void Gpu::shutdown() {
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

uint32_t Gpu::memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(physical, &mp);
    for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw std::runtime_error("no Vulkan memory type with the needed properties");
}

void Gpu::set_name(VkObjectType type, uint64_t handle, const char* name) {
    if (!debug_utils || !name || !vkSetDebugUtilsObjectNameEXT) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name;
    vkSetDebugUtilsObjectNameEXT(device, &info);
}

Image Gpu::create_image(VkFormat format, uint32_t w, uint32_t h, VkImageUsageFlags usage, const char* name) {
    Image img;
    img.format = format;
    img.width = w;
    img.height = h;
    const bool depth = format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM;
    img.aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = format;
    ci.extent = {w, h, 1};
    ci.mipLevels = ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = usage;
    vk_check(vkCreateImage(device, &ci, nullptr, &img.image), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, img.image, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    vk_check(vkAllocateMemory(device, &ai, nullptr, &img.memory), "vkAllocateMemory");
    vk_check(vkBindImageMemory(device, img.image, img.memory, 0), "vkBindImageMemory");
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = img.image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {img.aspect, 0, 1, 0, 1};
    vk_check(vkCreateImageView(device, &vi, nullptr, &img.view), "vkCreateImageView");
    set_name(VK_OBJECT_TYPE_IMAGE, (uint64_t)img.image, name);
    set_name(VK_OBJECT_TYPE_IMAGE_VIEW, (uint64_t)img.view, name);
    return img;
}

void Gpu::destroy(Image& img) {
    if (img.view) vkDestroyImageView(device, img.view, nullptr);
    if (img.image) vkDestroyImage(device, img.image, nullptr);
    if (img.memory) vkFreeMemory(device, img.memory, nullptr);
    img = Image();
}

Buffer Gpu::create_buffer(VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible, const char* name) {
    Buffer b;
    b.size = size;
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = size;
    bci.usage = usage;
    vk_check(vkCreateBuffer(device, &bci, nullptr, &b.buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, b.buffer, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    if (host_visible) {
        // Prefer cached memory for readback (reads from uncached memory are slow on GPUs).
        const VkMemoryPropertyFlags base = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        try {
            ai.memoryTypeIndex = memory_type(req.memoryTypeBits, base | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
        } catch (const std::runtime_error&) {
            ai.memoryTypeIndex = memory_type(req.memoryTypeBits, base);
        }
    } else {
        ai.memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    }
    vk_check(vkAllocateMemory(device, &ai, nullptr, &b.memory), "vkAllocateMemory");
    vk_check(vkBindBufferMemory(device, b.buffer, b.memory, 0), "vkBindBufferMemory");
    if (host_visible) vk_check(vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
    set_name(VK_OBJECT_TYPE_BUFFER, (uint64_t)b.buffer, name);
    return b;
}

void Gpu::destroy(Buffer& b) {
    if (b.buffer) vkDestroyBuffer(device, b.buffer, nullptr);
    if (b.memory) vkFreeMemory(device, b.memory, nullptr);  // unmaps implicitly
    b = Buffer();
}

VkShaderModule Gpu::create_shader(const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = bytes;
    ci.pCode = code;
    VkShaderModule m;
    vk_check(vkCreateShaderModule(device, &ci, nullptr, &m), "vkCreateShaderModule");
    return m;
}

void Gpu::init_storage_images(const std::vector<Image*>& images) {
    immediate([&](VkCommandBuffer cmd) {
        std::vector<VkImageMemoryBarrier> to_general;
        for (Image* img : images) {
            VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
            b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
            b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
            b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
            b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.image = img->image;
            b.subresourceRange = {img->aspect, 0, 1, 0, 1};
            to_general.push_back(b);
        }
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                             (uint32_t)to_general.size(), to_general.data());
        VkClearColorValue zero{};
        VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        for (Image* img : images) vkCmdClearColorImage(cmd, img->image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
        memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    });
}

void Gpu::immediate(const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd;
    vk_check(vkAllocateCommandBuffers(device, &ai, &cmd), "vkAllocateCommandBuffers");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    record(cmd);
    vk_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    vk_check(vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
    vk_check(vkQueueWaitIdle(queue), "vkQueueWaitIdle");
    vkFreeCommandBuffers(device, pool, 1, &cmd);
}

}  // namespace rrc_sample
