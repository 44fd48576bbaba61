// The device requirements (vk_requirements.h): one table for the query and
// for the checks at creation.
#include "vk_requirements.h"

#include <cstring>

namespace rrc {

const VkFormat kStorageFormats[7] = {VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT,
                                     VK_FORMAT_R8_UINT,    VK_FORMAT_R16_UINT,            VK_FORMAT_R32_UINT};

// Storage images of any format are written without a declared format (the
// kernel binds the host's outputs whatever their float format).
const RequiredFeature kRequiredFeatures[1] = {
    {&VkPhysicalDeviceFeatures::shaderStorageImageWriteWithoutFormat, "shaderStorageImageWriteWithoutFormat"}};

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

void check_enabled_features(const VkPhysicalDeviceFeatures& enabled, const char* what) {
    for (const RequiredFeature& f : kRequiredFeatures)
        if (!(enabled.*f.member))
            fail(RRC_ERROR_UNSUPPORTED, "%s->%s is VK_FALSE: rrc needs it enabled on the device (rrc_vulkan_get_requirements)", what, f.name);
}

}  // namespace rrc
