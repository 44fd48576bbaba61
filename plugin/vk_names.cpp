#include "vk_names.h"

// Only the tables: no Vulkan-Hpp dispatch, the library loads its entry points with volk.
#define VULKAN_HPP_DISPATCH_LOADER_DYNAMIC 1
#define VULKAN_HPP_NO_EXCEPTIONS
#include <vulkan/vulkan_format_traits.hpp>
#include <vulkan/vulkan_to_string.hpp>

#include <cstring>

namespace rrc {

std::string format_name(VkFormat format) { return vk::to_string(static_cast<vk::Format>(format)) + " (" + std::to_string((int)format) + ")"; }

namespace {

template <typename Test>
bool every_component(VkFormat format, Test test) {
    const vk::Format f = static_cast<vk::Format>(format);
    const uint8_t n = vk::componentCount(f);
    if (n == 0) return false;
    for (uint8_t c = 0; c < n; ++c)
        if (!test(vk::componentNumericFormat(f, c))) return false;
    return true;
}

}  // namespace

bool is_float_format(VkFormat format) {
    return every_component(format, [](const char* k) { return !std::strcmp(k, "SFLOAT") || !std::strcmp(k, "UFLOAT"); });
}

bool is_integer_format(VkFormat format) {
    return vk::componentCount(static_cast<vk::Format>(format)) != 0 &&
           !every_component(format, [](const char* k) { return std::strcmp(k, "UINT") && std::strcmp(k, "SINT"); });
}

}  // namespace rrc
