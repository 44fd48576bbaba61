// The reference's previous frame from the kernel's own outputs: the reference
// runs each frame from the kernel's stored state, so errors do not compound
// (tests/kernels/kernel_reference_test.cpp).
#pragma once

#include "reference/rrc_reference.h"
#include "support/rrc_test_context.h"

namespace rrc_test {

// Depth as the host passed it, every channel's history, age and weight (empty
// for channels without a confidence) as the kernel wrote them.
inline rrc_ref::PreviousFrame kernel_state(const std::vector<float>& depth, const FrameResult& k) {
    rrc_ref::PreviousFrame prev;
    prev.valid = true;
    prev.depth = depth;
    prev.channels.resize(k.values.size());
    for (size_t ch = 0; ch < k.values.size(); ++ch) {
        prev.channels[ch].history = k.values[ch];
        prev.channels[ch].age = k.age[ch];
        prev.channels[ch].weight = k.weight[ch];
    }
    return prev;
}

}  // namespace rrc_test
