// Helpers of the stability tests: per-frame input arrays that a whole batch
// keeps alive, one rrc_frame_run_batch call over them, a static "identity"
// reprojection, and a deterministic noise source.
//
// Why batches: the long cases run thousands of frames; one submission per
// few hundred frames keeps them to seconds on lavapipe.
#pragma once

#include "scenes/random.h"
#include "support/rrc_test_context.h"

#include <rrc/rrc.h>

#include <cstring>
#include <vector>

namespace rrc_stab {

// One frame's inputs, owned; empty vectors mean "not passed" (NULL).
struct FrameData {
    uint64_t index = 0;
    uint32_t reset = 0;
    std::vector<float> depth, reprojection;
    std::vector<std::vector<float>> samples, confidence;  // per channel
    std::vector<uint8_t> nocache;
    double view_proj[16] = {}, prev_view_proj[16] = {};
    float jitter[2] = {}, prev_jitter[2] = {};
    bool read_values = true;  // read back values, ages and weights (the mask and stats always are)
};

inline void identity(double m[16]) {
    std::memset(m, 0, 16 * sizeof(double));
    m[0] = m[5] = m[10] = m[15] = 1.0;
}

// A context whose pixels all hit from the second frame on: CAMERA
// reprojection with identity matrices over a constant STANDARD depth, so
// each pixel reprojects onto its own centre and the history is the pixel's
// own (NEAREST filter recommended: no neighbour enters).
inline rrc_context_desc static_desc(uint32_t width, uint32_t height, const std::vector<rrc_channel_desc>& channels) {
    rrc_context_desc d = rrc_test::context_desc(width, height, channels);
    d.depth_mode = RRC_DEPTH_MODE_STANDARD;
    d.reprojection = RRC_REPROJECTION_CAMERA;
    return d;
}

// Frame data for static_desc: depth 0.5, identity matrices, no jitter.
inline FrameData static_frame(uint32_t width, uint32_t height, uint64_t index) {
    FrameData f;
    f.index = index;
    f.depth.assign((size_t)width * height, 0.5f);
    identity(f.view_proj);
    identity(f.prev_view_proj);
    return f;
}

// The frame descriptor of `f` over its first `channel_count` channels (their
// inputs kept in `inputs`, which must outlive the descriptor's use).
inline rrc_frame_desc frame_desc_of(const FrameData& f, uint32_t channel_count, std::vector<rrc_channel_input>& inputs) {
    rrc_frame_desc d = rrc_test::frame_desc();
    d.frame_index = f.index;
    d.reset = f.reset;
    d.depth = f.depth.data();
    d.reprojection = f.reprojection.empty() ? nullptr : f.reprojection.data();
    std::memcpy(d.view_proj, f.view_proj, sizeof d.view_proj);
    std::memcpy(d.prev_view_proj, f.prev_view_proj, sizeof d.prev_view_proj);
    std::memcpy(d.jitter, f.jitter, sizeof d.jitter);
    std::memcpy(d.prev_jitter, f.prev_jitter, sizeof d.prev_jitter);
    d.nocache = f.nocache.empty() ? nullptr : f.nocache.data();
    inputs.clear();
    for (uint32_t c = 0; c < channel_count; ++c) {
        const float* conf = c < f.confidence.size() && !f.confidence[c].empty() ? f.confidence[c].data() : nullptr;
        inputs.push_back(rrc_test::channel_input(f.samples[c].data(), conf));
    }
    d.channel_count = channel_count;
    d.channels = inputs.data();
    return d;
}

// Runs `frames` in one rrc_frame_run_batch on a context made from `desc`
// (its channels in order).  Expects success; returns one result per frame.
inline std::vector<rrc_test::FrameResult> run_batch(rrc_context* ctx, const rrc_context_desc& desc, const std::vector<FrameData>& frames) {
    const size_t n = (size_t)desc.width * desc.height;
    const uint32_t nch = desc.channel_count;
    std::vector<rrc_test::FrameResult> results(frames.size());
    std::vector<rrc_frame_desc> descs(frames.size());
    std::vector<std::vector<rrc_channel_input>> inputs(frames.size());
    std::vector<rrc_frame_output> outputs(frames.size());
    std::vector<std::vector<rrc_channel_output>> channel_outputs(frames.size());
    for (size_t k = 0; k < frames.size(); ++k) {
        descs[k] = frame_desc_of(frames[k], nch, inputs[k]);

        rrc_test::FrameResult& r = results[k];
        r.mask.resize(n);
        r.values.resize(nch);
        r.age.resize(nch);
        r.weight.resize(nch);
        outputs[k] = rrc_host::frame_output();
        outputs[k].mask = r.mask.data();
        if (!frames[k].read_values) continue;
        channel_outputs[k].resize(nch);
        for (uint32_t c = 0; c < nch; ++c) {
            const rrc_channel_desc& ch = desc.channels[c];
            r.values[c].resize(n * ch.components);
            r.age[c].resize(n);
            rrc_channel_output& co = channel_outputs[k][c];
            co = rrc_host::channel_output();
            co.values = r.values[c].data();
            co.age = r.age[c].data();
            if (ch.confidence) {
                r.weight[c].resize(n);
                co.weight = r.weight[c].data();
            }
        }
        outputs[k].channel_count = nch;
        outputs[k].channels = channel_outputs[k].data();
    }
    rrc_result res = rrc_frame_run_batch(ctx, (uint32_t)frames.size(), descs.data(), outputs.data());
    EXPECT_EQ(res, RRC_SUCCESS) << rrc_result_to_string(res) << ": " << rrc_last_error();
    for (size_t k = 0; k < frames.size(); ++k) results[k].stats = outputs[k].stats;
    return results;
}

// Uniform in [0, 1) for (seed, frame, pixel, stream): every frame can be
// regenerated alone, so a CPU model sees exactly the kernel's inputs.
inline double noise01(uint64_t seed, int64_t frame, uint64_t pixel, uint64_t stream = 0) {
    return rrc_scene::uniform01(rrc_scene::hash4(seed, frame, pixel, stream));
}

}  // namespace rrc_stab
