// The shading cache's split path (docs/CONVENTIONS.md, "The shading cache"):
// rrc_frame_classify's outputs and the samples a host shades for
// rrc_frame_resolve, REUSE channels only at the listed quads.
#pragma once

#include "support/rrc_test_context.h"

#include <cmath>
#include <set>

namespace rrc_test {

// The frame as classify takes it: geometry only, no channel.
inline rrc_frame_desc geometry_of(rrc_frame_desc f) {
    f.channel_count = 0;
    f.channels = nullptr;
    return f;
}

// rrc_frame_classify's outputs for a width x height frame: the mask and a
// quad array of RRC_QUAD_LIST_BYTES / 4 words, all of them the capacity.
// Not copyable: `out` points into the arrays.
struct Classification {
    std::vector<uint8_t> mask;
    std::vector<uint32_t> quads;
    rrc_classify_output out;

    Classification(uint32_t width, uint32_t height)
        : mask((size_t)width * height),
          quads(RRC_QUAD_LIST_BYTES(width, height) / 4),
          out(rrc_host::rrc_struct<rrc_classify_output>(RRC_STRUCT_TYPE_CLASSIFY_OUTPUT)) {
        out.mask = mask.data();
        out.quads = quads.data();
        out.quad_capacity = (uint32_t)quads.size();
    }
    Classification(const Classification&) = delete;
    Classification& operator=(const Classification&) = delete;

    rrc_result run(rrc_context* ctx, const rrc_frame_desc& frame) { return rrc_frame_classify(ctx, &frame, &out); }
    // The quads classify listed, as a set.
    std::set<uint32_t> listed() const { return std::set<uint32_t>(quads.begin(), quads.begin() + out.quad_count); }
};

// What a host gives rrc_frame_resolve after classify listed `quads`: each
// channel of `full` (a frame's inputs, confidence and fallback kept) with its
// samples, a REUSE channel's only at the listed quads and NaN at every other
// pixel (what the host never shaded).  Not copyable: `desc` points into it.
struct HostSamples {
    std::vector<std::vector<float>> samples;
    std::vector<rrc_channel_input> inputs;
    rrc_resolve_desc desc;

    HostSamples(const std::vector<rrc_channel_desc>& channels, const rrc_frame_desc& full, const std::set<uint32_t>& quads, int W,
                int H)
        : samples(channels.size()), inputs(channels.size()), desc(rrc_host::rrc_struct<rrc_resolve_desc>(RRC_STRUCT_TYPE_RESOLVE_DESC)) {
        const size_t n = (size_t)W * H;
        for (size_t c = 0; c < channels.size(); ++c) {
            const uint32_t m = channels[c].components;
            const float* given = full.channels[c].samples;
            if (channels[c].blend != RRC_BLEND_REUSE) {
                samples[c].assign(given, given + n * m);
            } else {
                samples[c].assign(n * m, NAN);
                for (uint32_t q : quads)
                    for (int k = 0; k < 4; ++k) {
                        const int x = 2 * (int)(q & 0xFFFF) + (k & 1), y = 2 * (int)(q >> 16) + (k >> 1);
                        if (x >= W || y >= H) continue;
                        const size_t px = (size_t)y * W + x;
                        for (uint32_t j = 0; j < m; ++j) samples[c][m * px + j] = given[m * px + j];
                    }
            }
            inputs[c] = full.channels[c];
            inputs[c].samples = samples[c].data();
        }
        desc.channel_count = (uint32_t)inputs.size();
        desc.channels = inputs.data();
    }
    HostSamples(const HostSamples&) = delete;
    HostSamples& operator=(const HostSamples&) = delete;
};

}  // namespace rrc_test
