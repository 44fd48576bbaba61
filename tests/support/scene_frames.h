// Turns an analytic scene frame (tests/scenes) into the C API's frame
// description for a given reprojection source, keeping the arrays alive.
#pragma once

#include "rrc_descs.h"
#include "scenes/scene.h"

#include <rrc/rrc.h>

#include <cstring>
#include <vector>

namespace rrc_test {

struct SceneFrameInputs {
    rrc_scene::Frame frame;
    std::vector<float> reprojection;             // per the source's layout
    std::vector<uint32_t> object_id;             // the scene's ids as rrc object ids (sky: 0xFFFFFFFF)
    std::vector<std::vector<float>> confidence;  // per channel; empty = none
    std::vector<rrc_channel_input> inputs;
    rrc_frame_desc desc;
};

// channel_components: the context's channels in order (1 -> signal1, 4 -> signal4).
// confidence[i]: the channel takes a confidence, made from the truth (so it
// varies across the surface) as 0.25 + 0.75 * truth1.
inline void make_frame_inputs(SceneFrameInputs& in, rrc_reprojection source, const std::vector<uint32_t>& channel_components,
                              const std::vector<bool>& confidence) {
    const rrc_scene::Frame& f = in.frame;
    const size_t n = (size_t)f.width * f.height;
    in.reprojection.clear();
    if (source == RRC_REPROJECTION_PREV_CLIP) in.reprojection = f.prev_clip;
    if (source == RRC_REPROJECTION_MOTION_DEPTH) in.reprojection = f.motion;
    if (source == RRC_REPROJECTION_MOTION) {
        in.reprojection.resize(2 * n);
        for (size_t i = 0; i < n; ++i) {
            in.reprojection[2 * i] = f.motion[3 * i];
            in.reprojection[2 * i + 1] = f.motion[3 * i + 1];
        }
    }
    in.confidence.assign(channel_components.size(), {});
    in.inputs.clear();
    for (size_t c = 0; c < channel_components.size(); ++c) {
        if (confidence.size() > c && confidence[c]) {
            in.confidence[c].resize(n);
            for (size_t i = 0; i < n; ++i) in.confidence[c][i] = 0.25f + 0.75f * f.truth1[i];
        }
    }
    for (size_t c = 0; c < channel_components.size(); ++c) {
        rrc_channel_input ci;
        std::memset(&ci, 0, sizeof ci);
        ci.type = RRC_STRUCT_TYPE_CHANNEL_INPUT;
        ci.size = sizeof ci;
        ci.samples = channel_components[c] == 1 ? f.signal1.data() : f.signal4.data();
        ci.confidence = in.confidence[c].empty() ? nullptr : in.confidence[c].data();
        in.inputs.push_back(ci);
    }
    std::memset(&in.desc, 0, sizeof in.desc);
    in.desc.type = RRC_STRUCT_TYPE_FRAME_DESC;
    in.desc.size = sizeof in.desc;
    in.desc.frame_index = (uint64_t)f.index;
    in.desc.depth = f.depth.data();
    in.desc.reprojection = in.reprojection.empty() ? nullptr : in.reprojection.data();
    // Always given: a context without use_object_id ignores it.
    in.object_id.assign(f.object_id.begin(), f.object_id.end());
    in.desc.object_id = in.object_id.data();
    std::memcpy(in.desc.view_proj, f.view_proj, sizeof f.view_proj);
    std::memcpy(in.desc.prev_view_proj, f.prev_view_proj, sizeof f.prev_view_proj);
    std::memcpy(in.desc.jitter, f.jitter, sizeof f.jitter);
    std::memcpy(in.desc.prev_jitter, f.prev_jitter, sizeof f.prev_jitter);
    in.desc.channel_count = (uint32_t)in.inputs.size();
    in.desc.channels = in.inputs.data();
}

// make_frame_inputs for a context's channels: each one's components and
// whether it takes a confidence.
inline void make_frame_inputs(SceneFrameInputs& in, rrc_reprojection source, const std::vector<rrc_channel_desc>& channels) {
    std::vector<uint32_t> comps;
    std::vector<bool> conf;
    for (const rrc_channel_desc& ch : channels) {
        comps.push_back(ch.components);
        conf.push_back(ch.confidence != 0);
    }
    make_frame_inputs(in, source, comps, conf);
}

// A scene of width x height in one depth mode and format, up to far_plane
// (near and far: the scene's defaults, 0.1 and 100); the caller sets the rest.
inline rrc_scene::SceneConfig scene_config(int width, int height, rrc_depth_mode depth_mode,
                                           rrc_depth_format depth_format = RRC_DEPTH_FORMAT_FLOAT32,
                                           double far_plane = rrc_scene::SceneConfig().far_plane) {
    const rrc_scene::SceneConfig defaults;
    // In SceneConfig's member order; the members after depth_format keep their defaults.
    return {width, height, depth_mode, defaults.near_plane, far_plane, depth_format};
}

// The context that accumulates scene `sc` from `source` over `channels`
// (which must outlive the descriptor's use): the scene's extent, depth mode,
// depth format and planes.
inline rrc_context_desc scene_context_desc(const rrc_scene::SceneConfig& sc, rrc_reprojection source,
                                           const std::vector<rrc_channel_desc>& channels) {
    rrc_context_desc d = rrc_host::context_desc((uint32_t)sc.width, (uint32_t)sc.height, channels);
    d.depth_mode = sc.depth_mode;
    d.depth_format = sc.depth_format;
    d.reprojection = source;
    d.near_plane = (float)sc.near_plane;
    d.far_plane = (float)sc.far_plane;
    return d;
}

}  // namespace rrc_test
