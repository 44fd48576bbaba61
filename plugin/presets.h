// The presets' table (rrc.h, "Presets"): per application, variant and
// tuning version, the channel and context members it decides.
#pragma once

#include <rrc/rrc.h>

namespace rrc {

// Every member a channel preset decides; zero is off, or the library's
// default, as in rrc_channel_desc.  The members it does not list
// (rectify_gamma, blur_sigma, fill_depth_tolerance) it writes as 0.
struct PresetChannel {
    float lambda;
    rrc_blend blend;
    rrc_history_filter filter;
    uint32_t age_cap, fill_age, fill_radius;
    float fill_prior;
    uint32_t rectify, antilag;
    float antilag_gamma, antilag_threshold, blur_bound, view_lobe;
    uint32_t residual;
    float gate_kappa;  // 0.12: rows of earlier tunings leave it 0 (off)
};

// The context members an application fixes (rrc_context_preset).
struct PresetContext {
    bool fixes_geometry;  // OFFLINE: depth mode, motion source, units and axes, tau
    rrc_depth_mode depth_mode;
    rrc_reprojection reprojection;
    float tau;
    bool fixes_refresh;  // SHADING_CACHE: the refresh policy
    rrc_refresh_policy refresh_policy;
    uint32_t refresh_period, refresh_tiles[2], max_lifetime;
};

struct PresetRow {
    uint32_t version;  // the API version whose tuning these values are
    rrc_preset preset;
    bool base;  // the RRC_PRESET_FLAG_BASE variant
    PresetChannel channel;
    PresetContext context;
};

// The row rrc_channel_preset(preset, flags, tuning) takes; throws rrc::Error
// for a bad preset, flag or tuning (rrc.h, "Presets").
const PresetRow* find_preset(rrc_preset preset, uint32_t flags, uint32_t tuning);
// Writes the row's members within the caller's size (Versioning, rule 4).
void write_channel_preset(const PresetRow& row, rrc_channel_desc* caller);
// `read` is the caller's description as read by the struct rules (its size
// and width and height); throws for OFFLINE without width and height, and
// writes nothing then.
void write_context_preset(const PresetRow& row, const rrc_context_desc& read, rrc_context_desc* caller);

}  // namespace rrc
