// The per-frame table of live inputs: which of the kernel's inputs a
// configuration reads, from which binding on each path, in which format the
// standalone path keeps its copy and how the host lays out its CPU array.
// Descriptor writes, barriers, uploads and image creation all read this one
// table, so an input is live in exactly one place.
#pragma once

#include "accumulate_pipeline.h"
#include "config.h"
#include "frame.h"

#include <vector>

namespace rrc {

enum class InputRole { Depth, Reprojection, Nocache, ObjectId, Samples, Confidence, Fallback };

// The inputs of a channel (uploaded by resolve, not classify).
inline bool is_channel_input(InputRole r) { return r == InputRole::Samples || r == InputRole::Confidence || r == InputRole::Fallback; }

// Depth and object ids are kept from frame to frame (ViewState's ping-pong
// images): the standalone path uploads them into the frame's parity, not
// into an input image of its own.
inline bool kept_as_history(InputRole r) { return r == InputRole::Depth || r == InputRole::ObjectId; }

struct LiveInput {
    InputRole role;
    uint32_t slot;                // the channel slot (Samples, Confidence), else 0
    Binding own_binding;          // standalone: the library's copy, a storage image
    Binding host_binding;         // Vulkan path: the host's image through a sampler
    VkFormat own_format;          // standalone copy's format
    uint32_t host_components;     // standalone: floats (or bytes, Nocache) per pixel in the host's array
    uint32_t host_element_bytes;  // 4 (float) or 1 (uint8 Nocache)
};

// Every input the configuration reads, in upload order.
std::vector<LiveInput> live_inputs(const ContextConfig& config);

// The host's CPU array (standalone) or image (Vulkan) of one input.
const void* host_array(const Frame& frame, const LiveInput& input);
const rrc_vulkan_image& host_image(const Frame& frame, const LiveInput& input);

}  // namespace rrc
