#include "context_setup.h"

#include "rrc_descs.h"
#include "scene.h"

#include <cstdio>
#include <stdexcept>
#include <string>

namespace rrc_bench {

void LogCounter::callback(void* user, rrc_log_level level, const char* message) {
    if (level < RRC_LOG_WARNING) return;
    ++static_cast<LogCounter*>(user)->messages;
    std::fprintf(stderr, "rrc: %s\n", message);
}

ContextSetup::ContextSetup(const Config& c, LogCounter& log) {
    for (size_t i = 0; i < c.channels.size(); ++i) {
        const ChannelConfig& ch = c.channels[i];
        // lambda 0.6, the paper's 3/5, with the default (fixed) blend: a typical channel.
        channels_.push_back(rrc_host::channel(("signal" + std::to_string(i)).c_str(), ch.components, 0.6f, ch.precision,
                                              c.shading_cache != Config::Cache::Off ? RRC_BLEND_REUSE : RRC_BLEND_FIXED, ch.filter, 0,
                                              ch.confidence ? 1u : 0u));
        channels_.back().rectify = ch.rectify ? 1u : 0u;
        channels_.back().fill_age = ch.fill_age;
        channels_.back().view_lobe = ch.view_lobe;
        channels_.back().residual = ch.residual ? 1u : 0u;
        channels_.back().fill_radius = ch.fill_radius;
        channels_.back().gate_kappa = ch.gate_kappa;
        if (ch.preset && rrc_channel_preset(ch.preset, RRC_PRESET_FLAG_BASE, RRC_API_VERSION, &channels_.back()) != RRC_SUCCESS)
            throw std::runtime_error(std::string("rrc_channel_preset: ") + rrc_last_error());
    }
    desc_ = rrc_host::context_desc(c.width, c.height, channels_);
    desc_.depth_mode = RRC_DEPTH_MODE_REVERSED;
    desc_.depth_format = RRC_DEPTH_FORMAT_FLOAT32;  // depth arrives as R32F colour (.r)
    desc_.near_plane = kNear;  // plain MOTION linearises the depth with them
    desc_.far_plane = kFar;
    desc_.reprojection = c.source;
    desc_.use_nocache_mask = c.nocache ? 1u : 0u;
    desc_.use_object_id = c.object_id ? 1u : 0u;
    desc_.depth_test = c.depth_test;
    if (c.shading_cache != Config::Cache::Off) {
        desc_.refresh_policy = RRC_REFRESH_TILED;
        desc_.refresh_period = 4;
        desc_.refresh_tiles[0] = desc_.refresh_tiles[1] = 2;
    }
    desc_.log = &LogCounter::callback;
    desc_.log_user = &log;
}

}  // namespace rrc_bench
