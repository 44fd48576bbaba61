// What a host made by the bootstrap (vulkan_bootstrap.h) hands to rrc's
// interop API (include/rrc/rrc_vulkan.h): its device and its images.
// rrc-sample and the interop tests filled these the same way; now once.
#pragma once

#include "rrc_descs.h"
#include "vulkan_bootstrap.h"

#include <rrc/rrc_vulkan.h>

#include <stdexcept>
#include <string>

namespace rrc_host {

/** The bootstrap's instance, device and queue family, loader entry from volk. */
inline rrc_vulkan_device_desc vulkan_device_desc(const VulkanBootstrap& vk, uint32_t max_frames_in_flight) {
    auto d = rrc_struct<rrc_vulkan_device_desc>(RRC_STRUCT_TYPE_VULKAN_DEVICE_DESC);
    d.instance = vk.instance;
    d.physical_device = vk.physical;
    d.device = vk.device;
    d.queue_family_index = vk.family;
    d.vulkan_api_version = vk.api_version;
    d.get_instance_proc_addr = vkGetInstanceProcAddr;
    d.max_frames_in_flight = max_frames_in_flight;
    d.debug_utils_enabled = vk.debug_utils ? 1u : 0u;
    d.enabled_features = &vk.enabled_features;  // 0.11: rrc checks that its features are among them
    return d;
}

/** The device features rrc needs (rrc_vulkan_get_requirements): what a
 *  BootstrapOptions enables for it. */
inline VkPhysicalDeviceFeatures rrc_features() {
    auto r = rrc_struct<rrc_vulkan_requirements>(RRC_STRUCT_TYPE_VULKAN_REQUIREMENTS);
    if (rrc_vulkan_get_requirements(&r) != RRC_SUCCESS) throw std::runtime_error(std::string("rrc_vulkan_get_requirements: ") + rrc_last_error());
    return r.features;
}

/** `img` as the kernel sees it, in `layout` (final_layout 0: left as it was). */
inline rrc_vulkan_image vulkan_image(const Image& img, VkImageLayout layout) {
    return rrc_vulkan_image{img.image, img.view, img.format, layout, VK_IMAGE_LAYOUT_UNDEFINED};
}

}  // namespace rrc_host
