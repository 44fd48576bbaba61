// What rrc needs of a Vulkan device, written once: rrc_vulkan_get_requirements
// returns it, and both paths check a device against it at creation
// (rrc_vulkan.h, "Device requirements"; docs/guide/integration.md, "What rrc checks
// and what it cannot").  The query is device-free.
#pragma once

#include <rrc/rrc.h>
#include <rrc/rrc_vulkan.h>

#include <functional>

namespace rrc {

// The requirements as the query writes them (its type and size as the header's).
rrc_vulkan_requirements device_requirements();

// Refuses (RRC_ERROR_UNSUPPORTED, naming what is missing, and the device by
// props.deviceName) a physical device whose API version, features, limits or
// storage-image formats fall short.  `props` and `features` are the device's
// own; `supports_storage(format)` asks the device.
void check_physical_device_requirements(const VkPhysicalDeviceProperties& props, const VkPhysicalDeviceFeatures& features,
                                        const std::function<bool(VkFormat)>& supports_storage);

// Refuses (RRC_ERROR_UNSUPPORTED) a host's declared enabled features that
// lack one rrc needs (rrc_vulkan_device_desc.enabled_features, 0.11).
void check_enabled_features(const VkPhysicalDeviceFeatures& enabled, const char* what);

}  // namespace rrc
