// Per-frame parameters of the kernel from the frame record, including the
// CAMERA source's matrices, formed in double precision.
#pragma once

#include "accumulate_pipeline.h"
#include "config.h"
#include "frame.h"

namespace rrc {

FramePushConstants make_frame_constants(const ContextConfig& config, const Frame& frame, bool prev_valid);

// The view buffer's contents (compute/rrc_kernel_interface.h, RRC_BINDING_VIEW):
// Q = translate(-C) * inverse(VP_cur), column-major, then C_prev - C and the lighting's turn phi.
struct ViewBuffer {
    float Q[16];
    float d[4];
};
static_assert(sizeof(ViewBuffer) == RRC_VIEW_BUFFER_FLOATS * sizeof(float), "the GLSL block View");
ViewBuffer make_view_buffer(const Frame& frame);

}  // namespace rrc
