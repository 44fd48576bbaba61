// The sample's rrc channel settings, one per application.  They start from
// the library's presets (rrc_channel_preset; docs/reference/presets.md, and
// each application's guide in docs/guide/); an option the user gives
// (--lambda, --blend, --history-filter, --soft-age-cap, ...) changes a member,
// nothing else does.  rrc_stage.cpp turns them into rrc_channel_desc.
#pragma once

#include <rrc/rrc.h>

#include "shaders/signal_modes.h"

namespace rrc_sample {

/** One signal's rrc channel (include/rrc/rrc.h, rrc_channel_desc). */
struct ChannelSettings {
    float lambda = 0.6f;
    rrc_blend blend = RRC_BLEND_FIXED;
    rrc_history_filter filter = RRC_HISTORY_FILTER_BILINEAR;
    uint32_t age_cap = 0;  // 0: the library's default
    // 0.4 finishing steps (docs/CONVENTIONS.md, "Finishing steps"); zero = off / the library's default.
    uint32_t confidence = 0;          // the signal pass writes a per-sample confidence
    uint32_t rectify = 0;             // history rectification
    float rectify_gamma = 0.0f;
    float blur_sigma = 0.0f;          // RRC_HISTORY_FILTER_GAUSSIAN
    uint32_t fill_age = 0;            // the spatial fill for pixels younger than this
    uint32_t fill_radius = 0;
    float fill_depth_tolerance = 0.0f;
    float fill_prior = 0.0f;          // the fallback's weight in samples (needs a fallback image)
    // 0.5 the lag detector (docs/CONVENTIONS.md, "The lag detector"); zero = off / the library's default.
    uint32_t antilag = 0;
    float antilag_gamma = 0.0f;
    float antilag_threshold = 0.0f;
    // 0.6 the blur bound (docs/CONVENTIONS.md, "The blur bound"), px^2; 0 = off.
    float blur_bound = 0.0f;
    // 0.7 the view-dependent history (docs/CONVENTIONS.md, "The view-dependent history"), radians; 0 = off.
    float view_lobe = 0.0f;
    // 0.9 the residual (docs/CONVENTIONS.md, "The residual"): the channel accumulates the sample
    // less the fallback image, its base, and shows the result plus the base.  The sample's bases:
    // soft's stable PCSS estimate (README.md, "The soft residual"), which is then also the fill's
    // prior; pcf's kSamplePcfBaseTaps bilinear compares (README.md, "The pcf residual"); env's
    // filtered reflections (kSampleEnvBase; README.md, "The env residual").
    uint32_t residual = 0;
    // 0.12 the deviation gate (docs/CONVENTIONS.md, "The deviation gate"), kappa; 0 = off.
    float gate_kappa = 0.0f;
};

/** The env preset's base with RRC_PRESET_FLAG_BASE: four reflections into the environment
 *  box-filtered over their footprints (rrc-sample's --env-residual default, `filtered`;
 *  docs/guide/env-bump.md). */
constexpr uint32_t kSampleEnvBase = SAMPLE_ENV_BASE_FILTERED;

/** A lobe in pixels of the camera's vertical angle for --env-view-lobe-px (the rectification
 *  study's rows; docs/CONVENTIONS.md, "The view-dependent history"): alpha = px * fov_y / height. */
constexpr float kEnvViewLobePixels = 18.0f;

/** The pcf preset's base with RRC_PRESET_FLAG_BASE: this many bilinear shadow compares, as many
 *  as the per-frame signal's k = 4 taps (rrc-sample's --pcf-residual default; docs/guide/pcf-shadows.md). */
constexpr uint32_t kSamplePcfBaseTaps = 4;

/** rrc-sample's B where --blur-bound names a channel without --blur-bound-px2 (docs/measurements/PERFORMANCE.md,
 *  "The blur bound: what it buys, measured"). */
constexpr float kSampleBlurBound = 0.5f;
/** --gate's kappa where --gate-kappa is not given (docs/measurements/clean-input.md, "A temporal
 *  gate, simulated": the soft form's best threshold in the offline preset's model). */
constexpr float kSampleGateKappa = 2.0f;

/** A channel's settings as the library's description holds them. */
ChannelSettings settings_of(const rrc_channel_desc& d);

/** The library's presets for the sample's three signals (RRC_PRESET_PCF_SHADOWS, _ENV_BUMP,
 *  _SOFT_SHADOWS at tuning RRC_API_VERSION): with their bases, which rrc-sample renders by
 *  default, or without (--no-base).  Throws std::runtime_error if the library refuses. */
struct ChannelPresets {
    explicit ChannelPresets(bool base = true);
    ChannelSettings pcf, env, soft;
};

}  // namespace rrc_sample
