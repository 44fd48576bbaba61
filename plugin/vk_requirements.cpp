// The device requirements (vk_requirements.h): one table for the query and
// for the checks at creation.
#include "vk_requirements.h"

#include "error.h"
#include "vk_names.h"

#include <cstring>

namespace rrc {
namespace {

// The formats rrc's own images and the kernel's direct loads use as storage images.
const VkFormat kStorageFormats[] = {VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT,
                                   VK_FORMAT_R16G16_SFLOAT, VK_FORMAT_R8_UINT, VK_FORMAT_R16_UINT, VK_FORMAT_R32_UINT};

// The features rrc needs, by name.  Storage images of any format are written
// without a declared format (the kernel binds the host's outputs whatever
// their float format).
struct RequiredFeature {
    VkBool32 VkPhysicalDeviceFeatures::*member;
    const char* name;
};
const RequiredFeature kRequiredFeatures[] = {
    {&VkPhysicalDeviceFeatures::shaderStorageImageWriteWithoutFormat, "shaderStorageImageWriteWithoutFormat"}};

// Bindings 0-5, 9, 26 (1 each), 10-21, 24 and 25 (x4): compute/rrc_module_bindings.h.
constexpr uint32_t kStorageImagesPerStage = 64;

}  // namespace

rrc_vulkan_requirements device_requirements() {
    rrc_vulkan_requirements r;
    std::memset(&r, 0, sizeof r);
    r.type = RRC_STRUCT_TYPE_VULKAN_REQUIREMENTS;
    r.size = sizeof r;
    r.api_version = VK_API_VERSION_1_1;
    for (const RequiredFeature& f : kRequiredFeatures) r.features.*f.member = VK_TRUE;
    r.device_extension_count = 0;
    r.device_extensions = nullptr;
    r.max_per_stage_storage_images = kStorageImagesPerStage;
    r.optional_instance_extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    return r;
}

void check_physical_device_requirements(const VkPhysicalDeviceProperties& p, const VkPhysicalDeviceFeatures& f,
                                        const std::function<bool(VkFormat)>& supports_storage) {
    if (p.apiVersion < VK_API_VERSION_1_1)
        fail(RRC_ERROR_UNSUPPORTED, "device \"%s\" supports Vulkan %u.%u, rrc needs 1.1", p.deviceName, VK_API_VERSION_MAJOR(p.apiVersion),
             VK_API_VERSION_MINOR(p.apiVersion));
    for (const RequiredFeature& r : kRequiredFeatures)
        if (!(f.*r.member)) fail(RRC_ERROR_UNSUPPORTED, "device \"%s\" lacks the feature %s", p.deviceName, r.name);
    if (p.limits.maxPerStageDescriptorStorageImages < kStorageImagesPerStage)
        fail(RRC_ERROR_UNSUPPORTED, "device \"%s\" allows %u storage images per stage, the kernel needs %u", p.deviceName,
             p.limits.maxPerStageDescriptorStorageImages, kStorageImagesPerStage);
    for (VkFormat fmt : kStorageFormats)
        if (!supports_storage(fmt))
            fail(RRC_ERROR_UNSUPPORTED, "device \"%s\": %s is not usable as a storage image", p.deviceName, format_name(fmt).c_str());
}

void check_enabled_features(const VkPhysicalDeviceFeatures& enabled, const char* what) {
    for (const RequiredFeature& f : kRequiredFeatures)
        if (!(enabled.*f.member))
            fail(RRC_ERROR_UNSUPPORTED, "%s->%s is VK_FALSE: rrc needs it enabled on the device (rrc_vulkan_get_requirements)", what, f.name);
}

}  // namespace rrc
