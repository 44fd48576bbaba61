// A SPIR-V module with the default of one integer specialization constant
// rewritten.  rrc_sample's ComputeKernel takes no VkSpecializationInfo, and
// a pipeline that is given none uses the module's default (Vulkan spec,
// "Specialization Constants"), so rewriting the default specialises the
// shader exactly as VkSpecializationInfo would: perlin.glsl's kOctaves.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rrc_cache {

/** `words` (a SPIR-V module of `bytes` bytes) with the OpSpecConstant decorated SpecId `id`
 *  set to `value`.  Throws std::runtime_error if the module has no such 32-bit constant. */
std::vector<uint32_t> with_spec_constant(const uint32_t* words, size_t bytes, uint32_t id, uint32_t value);

/** The default of the OpSpecConstant decorated SpecId `id`; throws if there is none. */
uint32_t spec_constant(const std::vector<uint32_t>& module, uint32_t id);

}  // namespace rrc_cache
