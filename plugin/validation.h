// Argument validation of every descriptor the C API accepts.  Device-free:
// rrc_validate_context_desc() and fuzzers call it without any Vulkan object.
#pragma once

#include "config.h"

struct rrc_vulkan_device_desc;  // include/rrc/rrc_vulkan.h

namespace rrc {

// Checks a frame (and the optional output description) against the context's
// configuration; throws rrc::Error naming the field.
void validate_frame(const ContextConfig& config, const rrc_frame_desc* frame, const rrc_frame_output* output);

// Checks the host's Vulkan objects for rrc_vulkan_context_create.
void validate_vulkan_device_desc(const ::rrc_vulkan_device_desc* device);

}  // namespace rrc
