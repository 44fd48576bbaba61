// The sample's rrc channel settings, one per application: what the command
// line sets (--lambda, --blend, --history-filter, --soft-age-cap) and what
// rrc_stage.cpp turns into rrc_channel_desc.
#pragma once

#include <rrc/rrc.h>

namespace rrc_sample {

/** One signal's rrc channel (include/rrc/rrc.h, rrc_channel_desc). */
struct ChannelSettings {
    float lambda = 0.6f;
    rrc_blend blend = RRC_BLEND_FIXED;
    rrc_history_filter filter = RRC_HISTORY_FILTER_BILINEAR;
    uint32_t age_cap = 0;  // 0: the library's default
};

/** The sample's presets, one per application (README.md, "The three signals": the
 *  values and the sweep that chose them). */
struct ChannelPresets {
    ChannelSettings pcf{0.6f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0};
    ChannelSettings env{0.6f, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0};
    ChannelSettings soft{0.0f, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_BILINEAR, 64};
};

}  // namespace rrc_sample
