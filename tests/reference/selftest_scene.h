// Small owned-array scene builder for the reference self-tests: fills the C
// API descriptors (with the shared builders of host_sample/common/rrc_descs.h)
// and keeps every array they point to alive.
#ifndef RRC_REFERENCE_SELFTEST_SCENE_H
#define RRC_REFERENCE_SELFTEST_SCENE_H

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "rrc_descs.h"
#include "rrc_reference.h"

namespace rrc_ref_test {

struct Scene {
    int W, H;
    rrc_context_desc ctx{};
    std::vector<rrc_channel_desc> channel_descs;
    std::vector<float> depth, reprojection;
    std::vector<uint8_t> nocache;
    std::vector<std::vector<float>> samples, confidence;
    std::vector<rrc_channel_input> inputs;
    rrc_frame_desc frame{};

    Scene(int width, int height, rrc_depth_mode mode, rrc_reprojection source) : W(width), H(height) {
        ctx = rrc_host::context_desc(width, height, channel_descs);
        ctx.depth_mode = mode;
        ctx.reprojection = source;
        ctx.near_plane = 0.1f;  // plain MOTION on NDC depth linearises with these
        ctx.far_plane = 100.0f;
        frame = rrc_host::frame_desc();
        for (int k = 0; k < 16; ++k)  // identity cameras
            frame.view_proj[k] = frame.prev_view_proj[k] = (k % 5 == 0) ? 1.0 : 0.0;
        depth.assign(size(), 0.5f);
        int n = source == RRC_REPROJECTION_PREV_CLIP      ? 4
                : source == RRC_REPROJECTION_MOTION       ? 2
                : source == RRC_REPROJECTION_MOTION_DEPTH ? 3
                                                          : 0;
        reprojection.assign(size() * n, 0.0f);
        nocache.assign(size(), 0);
    }
    size_t size() const { return static_cast<size_t>(W) * H; }
    size_t at(int i, int j) const { return static_cast<size_t>(j) * W + i; }

    // Returns the channel's index.
    int add_channel(unsigned components, float lambda, rrc_blend blend = RRC_BLEND_FIXED,
                    rrc_history_filter filter = RRC_HISTORY_FILTER_BILINEAR, rrc_history_precision precision = RRC_HISTORY_FP32,
                    bool with_confidence = false, unsigned age_cap = 0) {
        char name[RRC_MAX_NAME];
        std::snprintf(name, sizeof name, "c%zu", channel_descs.size());
        rrc_channel_desc d = rrc_host::channel(name, components, lambda, precision, blend, filter, age_cap, with_confidence);
        channel_descs.push_back(d);
        samples.emplace_back(size() * components, 0.0f);
        confidence.emplace_back(with_confidence ? size() : 0, 1.0f);
        return static_cast<int>(channel_descs.size()) - 1;
    }

    // Points the descriptors at the owned arrays (call after any resize).
    const rrc_frame_desc& desc() {
        ctx.channel_count = static_cast<uint32_t>(channel_descs.size());
        ctx.channels = channel_descs.data();
        inputs.clear();
        for (size_t c = 0; c < channel_descs.size(); ++c) {
            inputs.push_back(rrc_host::channel_input(samples[c].data(), confidence[c].empty() ? nullptr : confidence[c].data()));
        }
        frame.depth = depth.data();
        frame.reprojection = reprojection.empty() ? nullptr : reprojection.data();
        frame.nocache = ctx.use_nocache_mask ? nocache.data() : nullptr;
        frame.channel_count = ctx.channel_count;
        frame.channels = inputs.data();
        return frame;
    }

    rrc_ref::FrameResult run(const rrc_ref::PreviousFrame& prev, const rrc_ref::Options& o = {}) {
        const rrc_frame_desc& f = desc();
        return rrc_ref::run_frame(ctx, prev, f, o);
    }

    // A previous frame with this scene's depth and a given state per channel.
    rrc_ref::PreviousFrame previous(std::vector<std::vector<float>> history, uint16_t age, float weight = 1.0f) const {
        rrc_ref::PreviousFrame p;
        p.valid = true;
        p.depth = depth;
        for (size_t c = 0; c < channel_descs.size(); ++c) {
            rrc_ref::ChannelHistory h;
            h.history = std::move(history[c]);
            h.age.assign(size(), age);
            if (channel_descs[c].confidence) h.weight.assign(size(), weight);
            p.channels.push_back(std::move(h));
        }
        return p;
    }
};

// The deviation gate's state as stored (docs/CONVENTIONS.md, "The deviation
// gate"): beta and sqrt(varsigma) rounded to fp16, varsigma read back as the
// rounded root's square.
inline double stored_beta(double beta) { return rrc_ref::fp16_round(beta); }
inline double stored_sq(double sq) {
    const double r = rrc_ref::fp16_round(std::sqrt(sq));
    return r * r;
}

}  // namespace rrc_ref_test

#endif
