// Facts about the host's VkFormats that validation and the interop barriers
// both need.  Header-only and device-free (the descriptor fuzzer uses it).
#pragma once

#include <vulkan/vulkan_core.h>

namespace rrc {

inline bool has_stencil(VkFormat f) {
    return f == VK_FORMAT_D16_UNORM_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}
inline bool is_depth_format(VkFormat f) {
    return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_X8_D24_UNORM_PACK32 || f == VK_FORMAT_D32_SFLOAT || has_stencil(f);
}

}  // namespace rrc
