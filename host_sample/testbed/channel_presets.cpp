// The sample's channels from the library's presets (channel_presets.h).
#include "channel_presets.h"

#include <stdexcept>
#include <string>

namespace rrc_sample {

ChannelSettings settings_of(const rrc_channel_desc& d) {
    ChannelSettings s;
    s.lambda = d.lambda, s.blend = d.blend, s.filter = d.filter, s.age_cap = d.age_cap, s.confidence = d.confidence;
    s.rectify = d.rectify, s.rectify_gamma = d.rectify_gamma, s.blur_sigma = d.blur_sigma;
    s.fill_age = d.fill_age, s.fill_radius = d.fill_radius, s.fill_depth_tolerance = d.fill_depth_tolerance, s.fill_prior = d.fill_prior;
    s.antilag = d.antilag, s.antilag_gamma = d.antilag_gamma, s.antilag_threshold = d.antilag_threshold;
    s.blur_bound = d.blur_bound, s.view_lobe = d.view_lobe, s.residual = d.residual;
    s.gate_kappa = d.gate_kappa;
    return s;
}

namespace {

ChannelSettings preset(rrc_preset p, bool base) {
    rrc_channel_desc d{RRC_STRUCT_TYPE_CHANNEL_DESC, nullptr, sizeof d};
    if (rrc_channel_preset(p, base ? RRC_PRESET_FLAG_BASE : 0u, RRC_API_VERSION, &d) != RRC_SUCCESS)
        throw std::runtime_error(std::string("rrc_channel_preset: ") + rrc_last_error());
    return settings_of(d);
}

}  // namespace

ChannelPresets::ChannelPresets(bool base)
    : pcf(preset(RRC_PRESET_PCF_SHADOWS, base)), env(preset(RRC_PRESET_ENV_BUMP, base)), soft(preset(RRC_PRESET_SOFT_SHADOWS, base)) {}

}  // namespace rrc_sample
