// Per-frame parameters of the kernel from the frame record, including the
// CAMERA source's matrices, formed in double precision.
#pragma once

#include "accumulate_pipeline.h"
#include "config.h"
#include "frame.h"

namespace rrc {

FramePushConstants make_frame_constants(const ContextConfig& config, const Frame& frame, bool prev_valid);

}  // namespace rrc
