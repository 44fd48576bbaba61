// Reads and writes one golden case as a single EXR: per frame f (0, 1) the
// inputs `f<f>.Z`, `f<f>.reproj.<k>`, `f<f>.<channel>.<k>`,
// `f<f>.<channel>.conf`, the matrices and jitter as string attributes, and
// the reference's frame-1 outputs `expected.<channel>.<k>`,
// `expected.<channel>.age`, `expected.<channel>.weight`, `expected.rrc.mask`
// and `expected.rrc.near_threshold`, `expected.rrc.near_nearest_edge`,
// `expected.rrc.uv_prev.X/Y` (where the tolerance's history spread is taken).
#pragma once

#include "golden/golden_cases.h"
#include "reference/rrc_reference.h"
#include "support/scene_frames.h"

#include <exr_io.h>

namespace rrc_golden {

// One frame's inputs as arrays, in the C API's layout.
struct FrameArrays {
    std::vector<float> depth, reprojection;
    std::vector<std::vector<float>> samples, confidence;
    double view_proj[16] = {}, prev_view_proj[16] = {};
    float jitter[2] = {}, prev_jitter[2] = {};
    std::vector<rrc_channel_input> inputs;
    rrc_frame_desc desc;
    void bind(const GoldenCase& c);  // fills inputs and desc from the arrays
};

struct GoldenData {
    FrameArrays frames[2];
    rrc_ref::FrameResult expected;  // frame 1: mask, channels, near_* flags
};

rrc_context_desc context_for(const GoldenCase& c, std::vector<rrc_channel_desc>& channels);
FrameArrays arrays_from_scene(const GoldenCase& c, rrc_test::SceneFrameInputs& in);
void write_golden(const std::string& path, const GoldenCase& c, const GoldenData& data);
GoldenData read_golden(const std::string& path, const GoldenCase& c);
// Runs the reference over the two frames (what make_golden writes).
GoldenData compute_golden(const GoldenCase& c);

}  // namespace rrc_golden
