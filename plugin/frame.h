// One frame as the library sees it, whichever public descriptor it came
// from (rrc_frame_desc: CPU arrays; rrc_vulkan_frame_desc: the host's
// images).  Read by read_frame (struct rules of struct_reader.h), checked by
// validate_frame (validation.h), turned into push constants by
// make_frame_constants and into bindings by the accumulator core.
#pragma once

#include "config.h"

#include <rrc/rrc.h>
#include <rrc/rrc_vulkan.h>

#include <array>
#include <cstdint>
#include <vector>

namespace rrc {

// Which public path a frame came from: decides only where its inputs live.
enum class FramePath { Standalone, Vulkan };

struct FrameChannel {
    // Standalone: CPU arrays.
    const float* samples = nullptr;
    const float* confidence = nullptr;
    const float* fallback = nullptr;  // the spatial fill's (0.4)
    // Vulkan: the host's images.
    rrc_vulkan_image samples_image{}, confidence_image{}, output_image{}, age_image{}, fallback_image{};
};

struct Frame {
    FramePath path = FramePath::Standalone;
    uint64_t frame_index = 0;
    bool reset = false;
    uint32_t view = 0;            // the view this frame writes
    uint32_t reproject_from = 0;  // 0: its own; v + 1: view v (validated against the context's view count)
    uint32_t source() const { return reproject_from ? reproject_from - 1 : view; }
    double view_proj[16] = {}, prev_view_proj[16] = {};
    double camera_position[3] = {}, prev_camera_position[3] = {};  // 0.7: read where a channel has a view lobe
    float lighting_turn = 0.0f;                                     // 0.8: phi, added to the view turn
    float jitter[2] = {}, prev_jitter[2] = {};
    uint32_t channel_count = 0;
    std::array<FrameChannel, RRC_MAX_CHANNELS> channels{};
    bool channels_given = false;  // the descriptor's channel array pointer was not NULL

    // Standalone inputs.
    const float* depth = nullptr;
    const float* reprojection = nullptr;
    const uint8_t* nocache = nullptr;
    const uint32_t* object_id = nullptr;

    // Vulkan inputs and outputs.
    VkCommandBuffer command_buffer = VK_NULL_HANDLE;
    rrc_vulkan_image depth_image{}, reprojection_image{}, nocache_image{}, mask_image{}, object_id_image{};
    VkBuffer stats_buffer = VK_NULL_HANDLE;
    VkDeviceSize stats_offset = 0;
    VkDeviceSize stats_buffer_size = 0;  // 0: not stated (a caller before 0.10)
    bool storage_inputs = false;  // the host's input images are read as storage images (rrc_vulkan_frame_desc)
    bool split_outputs = false;   // classify and resolve share the host's outputs (rrc_vulkan_frame_desc, 0.5)
    bool count_io = false;        // the frame also counts its image operations (rrc_vulkan_frame_desc, 0.13)
    // The host's stated image extents (rrc_vulkan_image_extents on frame.next, 0.11); unchecked when not given.
    bool extents_given = false;
    std::vector<rrc_vulkan_image_extent> extents;
};

// Where a standalone frame's results go (rrc_frame_output read by the struct
// rules); `caller` is written back only up to its size.
struct FrameOutputs {
    rrc_frame_output* caller = nullptr;  // NULL: nothing is read back
    uint8_t* mask = nullptr;
    uint32_t channel_count = 0;  // 0 or the context's
    struct Channel {
        float* values = nullptr;
        uint16_t* age = nullptr;
        float* weight = nullptr;
    };
    std::array<Channel, RRC_MAX_CHANNELS> channels{};
};

// Read a public descriptor into a Frame (struct rules only: size, strides,
// next chains, zero tails).  Throws rrc::Error naming the field.  The
// channel count is bounded by the context's so `channels` never overflows.
Frame read_frame(const rrc_frame_desc* desc, size_t context_channels);
Frame read_frame(const rrc_vulkan_frame_desc* desc, size_t context_channels);
FrameOutputs read_outputs(rrc_frame_output* output, size_t context_channels);
// rrc_resolve_desc: a Frame holding only its channels.
Frame read_resolve(const rrc_resolve_desc* desc, size_t context_channels);

}  // namespace rrc
