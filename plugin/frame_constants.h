// Per-frame parameters of the kernel from the host's frame description,
// including the CAMERA source's matrices, formed in double precision.
#pragma once

#include "accumulate_pipeline.h"
#include "config.h"

namespace rrc {

FramePushConstants make_frame_constants(const ContextConfig& config, const rrc_frame_desc& frame, bool prev_valid);

}  // namespace rrc
