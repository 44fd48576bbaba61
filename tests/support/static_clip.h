// The PREV_CLIP input of a camera that does not move: the "every pixel can
// hit" baseline of the API tests, written once rather than as a loop in each.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rrc_test {

// Each pixel's own clip position (pixel centres, w = 1) at NDC depth z.
inline std::vector<float> static_prev_clip(uint32_t width, uint32_t height, float z) {
    std::vector<float> clip;
    clip.reserve((size_t)width * height * 4);
    for (size_t k = 0; k < (size_t)width * height; ++k) {
        const float x = 2.0f * ((float)(k % width) + 0.5f) / (float)width - 1.0f;
        const float y = 2.0f * ((float)(k / width) + 0.5f) / (float)height - 1.0f;
        clip.insert(clip.end(), {x, y, z, 1.0f});
    }
    return clip;
}

}  // namespace rrc_test
