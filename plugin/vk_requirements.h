// What rrc needs of a Vulkan device, written once: rrc_vulkan_get_requirements
// returns it, and both paths check a device against it at creation
// (rrc_vulkan.h, "Device requirements"; docs/INTEGRATION.md, "What rrc checks
// and what it cannot").  The query is device-free.
#pragma once

#include <rrc/rrc.h>
#include <rrc/rrc_vulkan.h>

#include <string>

namespace rrc {

// The requirements as the query writes them (its type and size as the header's).
rrc_vulkan_requirements device_requirements();

// Refuses (RRC_ERROR_UNSUPPORTED, naming what is missing) a physical device
// whose properties, features or storage-image formats fall short.  `props`
// and `features` are the device's own; `format_supports_storage(format)`
// asks the device; messages name it by props.deviceName.
template <typename FormatStorage>
void check_physical_device_requirements(const VkPhysicalDeviceProperties& props, const VkPhysicalDeviceFeatures& features,
                                        FormatStorage format_supports_storage);

// Refuses (RRC_ERROR_UNSUPPORTED) a host's declared enabled features that
// lack one rrc needs (rrc_vulkan_device_desc.enabled_features, 0.11).
void check_enabled_features(const VkPhysicalDeviceFeatures& enabled, const char* what);

// The formats rrc's own images and the kernel's direct loads use as storage images.
extern const VkFormat kStorageFormats[7];
// The features rrc needs, by name (a VkBool32 member of VkPhysicalDeviceFeatures each).
struct RequiredFeature {
    VkBool32 VkPhysicalDeviceFeatures::*member;
    const char* name;
};
extern const RequiredFeature kRequiredFeatures[1];
// Bindings 0-5, 9, 26 (1 each), 10-21, 24 and 25 (x4): compute/rrc_module_bindings.h.
constexpr uint32_t kStorageImagesPerStage = 64;

}  // namespace rrc

#include "error.h"
#include "vk_names.h"

namespace rrc {

template <typename FormatStorage>
void check_physical_device_requirements(const VkPhysicalDeviceProperties& p, const VkPhysicalDeviceFeatures& f,
                                        FormatStorage format_supports_storage) {
    if (p.apiVersion < VK_API_VERSION_1_1)
        fail(RRC_ERROR_UNSUPPORTED, "device \"%s\" supports Vulkan %u.%u, rrc needs 1.1", p.deviceName, VK_API_VERSION_MAJOR(p.apiVersion),
             VK_API_VERSION_MINOR(p.apiVersion));
    for (const RequiredFeature& r : kRequiredFeatures)
        if (!(f.*r.member)) fail(RRC_ERROR_UNSUPPORTED, "device \"%s\" lacks the feature %s", p.deviceName, r.name);
    if (p.limits.maxPerStageDescriptorStorageImages < kStorageImagesPerStage)
        fail(RRC_ERROR_UNSUPPORTED, "device \"%s\" allows %u storage images per stage, the kernel needs %u", p.deviceName,
             p.limits.maxPerStageDescriptorStorageImages, kStorageImagesPerStage);
    for (VkFormat fmt : kStorageFormats)
        if (!format_supports_storage(fmt))
            fail(RRC_ERROR_UNSUPPORTED, "device \"%s\": %s is not usable as a storage image", p.deviceName, format_name(fmt).c_str());
}

}  // namespace rrc
