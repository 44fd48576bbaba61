// Vulkan's names and format facts for messages and checks, from Vulkan-Hpp's
// tables (vulkan_to_string.hpp, vulkan_format_traits.hpp), not a copy of
// them.  Device-free: validation and the descriptor fuzzer use it.
#pragma once

#include <vulkan/vulkan_core.h>

#include <string>

namespace rrc {

// "R8Uint (13)": the format's name and its value, as a host may grep either.
std::string format_name(VkFormat format);
// Every component a float (SFLOAT, UFLOAT): what a storage output must be.
bool is_float_format(VkFormat format);
// Some component an integer (UINT, SINT); false for UNDEFINED.  A
// depth/stencil format's stencil counts: test is_depth_format first.
bool is_integer_format(VkFormat format);

}  // namespace rrc
