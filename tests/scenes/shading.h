// Noise-free analytic "shading" of the scene surfaces: the signals' truth.
//
// Every value is a smooth function of the object id and the OBJECT-space hit
// point, so the pattern sticks to a moving surface exactly as a texture
// would: a correct cache hit fetches the same truth it would have computed.
// Values lie in [0, 1].  Patterns are soft (smoothstep-blurred) checkers and
// sine bands a few pixels wide at the default resolution, so bilinear
// resampling of history is visible but not dominant.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace rrc_scene {

// Fixed sky ("background") values of the two signals.
constexpr double kSky1 = 0.75;
inline glm::dvec4 sky4() { return glm::dvec4(0.45, 0.65, 0.95, 1.0); }

// 1-component truth (a shadow-like term): a blurred 3-D checker.
double shade1(int32_t object_id, const glm::dvec3& p_object);

// 4-component truth (a colour-like term): three sine bands and a coarser checker.
glm::dvec4 shade4(int32_t object_id, const glm::dvec3& p_object);

}  // namespace rrc_scene
