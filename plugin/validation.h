// Argument validation of every descriptor the C API accepts, one function
// per kind of descriptor, whichever path (standalone or Vulkan) it came
// from.  Device-free: rrc_validate_context_desc() and the fuzzers call it
// without any Vulkan object.
#pragma once

#include "config.h"
#include "frame.h"

namespace rrc {

// Checks a frame (and the optional outputs) against the context's
// configuration; throws rrc::Error naming the field.  stats_alignment: the
// device's minStorageBufferOffsetAlignment (Vulkan path), 0 to skip.
void validate_frame(const ContextConfig& config, const Frame& frame, const FrameOutputs* outputs, uint64_t stats_alignment);
// Its three parts: what classify reads (depth, reprojection, masks, ids, the
// statistics buffer), what resolve adds (the channels), and the outputs.
void validate_geometry(const ContextConfig& config, const Frame& frame, uint64_t stats_alignment);
void validate_channels(const ContextConfig& config, const Frame& frame);
void validate_outputs(const ContextConfig& config, const FrameOutputs* outputs);

// A host buffer's range: `bytes` at `offset` within the `size` the host
// states (Vulkan cannot report a buffer's size); RRC_ERROR_SIZE_MISMATCH names both.
void check_range(const char* offset_name, uint64_t offset, uint64_t bytes, const char* size_name, uint64_t size, const char* what);

// Reads and checks a standalone frame in one call (rrc_frame_run's order).
void validate_frame(const ContextConfig& config, const rrc_frame_desc* frame, rrc_frame_output* output);

// Checks the host's Vulkan objects for rrc_vulkan_context_create and returns
// them as read by the struct rules.
rrc_vulkan_device_desc validate_vulkan_device_desc(const rrc_vulkan_device_desc* device);

}  // namespace rrc
