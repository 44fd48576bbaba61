// The device images of one configuration: the host inputs the kernel and the
// roof both read (one set per camera pose), the outputs both write, and the
// "previous frame" state the roof reads in place of the library's own
// history (which the public API does not expose).  Every image is created
// STORAGE | SAMPLED | TRANSFER and lives in GENERAL: rrc samples it, the
// roof loads it as a storage image, the checks read it back.
#pragma once

#include "config.h"
#include "scene.h"
#include "vulkan_bootstrap.h"

#include <vector>

namespace rrc_bench {

using rrc_host::Image;
using rrc_host::VulkanBootstrap;

struct PoseImages {
    Image depth;         // R32_SFLOAT
    Image reprojection;  // PREV_CLIP, MOTION_DEPTH: RGBA32F (no 3-component storage format); MOTION: RG32F; CAMERA: none
    Image object_id;     // R32_UINT (with object ids)
};

struct BenchImages {
    PoseImages poses[2];
    std::vector<Image> samples;     // per channel, R32F or RGBA32F (what renderers write; fp16 history or not)
    std::vector<Image> confidence;  // per channel, R32F (empty Image without confidence)
    std::vector<Image> base;        // per channel, as samples (empty Image without residual): the residual's base
    Image nocache;                  // R8_UINT (with nocache)
    // Outputs written by the kernel and by the roof alike.
    std::vector<Image> values;   // per channel, at channel_format()
    std::vector<Image> age_out;  // per channel, R16_UINT
    Image mask;                  // R8_UINT
    // The roof's previous-frame state and its own copies.
    Image prev_depth, prev_object_id, depth_copy, object_id_copy;
    std::vector<Image> history, age_in, weight_in, weight_out;
};

/** The history and output format of a channel: R16F / RGBA16F / R32F / RGBA32F. */
VkFormat channel_format(const ChannelConfig& c);
/** Bytes of one texel of the formats the bench uses. */
uint32_t texel_bytes(VkFormat format);
/** Bytes of the whole image (width * height * texel). */
uint64_t image_bytes(const Image& image);

BenchImages create_images(VulkanBootstrap& vk, const Config& config, const SceneInputs& scene);
void destroy_images(VulkanBootstrap& vk, BenchImages& images);

/** Uploads floats converted to `image`'s format (R16F/RGBA16F take halves). */
void upload_floats(VulkanBootstrap& vk, const Image& image, const std::vector<float>& data);

}  // namespace rrc_bench
