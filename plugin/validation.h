// Argument validation of every descriptor the C API accepts.  Device-free:
// rrc_validate_context_desc() and fuzzers call it without any Vulkan object.
#pragma once

#include "config.h"

namespace rrc {

// Checks a frame (and the optional output description) against the context's
// configuration; throws rrc::Error naming the field.
void validate_frame(const ContextConfig& config, const rrc_frame_desc* frame, const rrc_frame_output* output);

}  // namespace rrc
