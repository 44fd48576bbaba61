// The context's settings with every "zero means default" resolved, plus the
// small scalar rules (background, invalid depth, linearisation, epsilon).
#ifndef RRC_REFERENCE_PARAMS_H
#define RRC_REFERENCE_PARAMS_H

#include <rrc/rrc.h>

#include <vector>

#include "error_bound.h"

namespace rrc_ref {

// Every row of compute/rrc_channel_options.def as the host set it, 0 read as
// the row's default (the table's rule, docs/design/adding-an-option.md): what
// an option added since carries to the reference's math without a member of
// its own.  The options above that predate the table keep their own members.
struct TableOptions {
#define RRC_CHANNEL_OPTION(member, ...) double member = 0.0;
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
};

struct ChannelParams {
    unsigned components;
    bool fp16;  // the history actually stored in fp16 (asked for, and not promoted to fp32)
    double lambda;
    rrc_blend blend;
    rrc_history_filter filter;
    unsigned age_cap;
    bool confidence;
    // 0.4 finishing steps (docs/CONVENTIONS.md "Finishing steps (0.4)"), defaults resolved.
    bool rectify = false;
    double rectify_gamma = 1.0;  // gamma
    double blur_g = 0.125;       // GAUSSIAN: g = blur_sigma^2 / 2 (the default sigma 0.5)
    unsigned fill_age = 0;       // T; 0 = no fill
    int fill_radius = 2;         // r
    double fill_tau = 0.005;     // fill_depth_tolerance
    double fill_prior = 0.0;     // P; 0 = no fallback
    // 0.5 the lag detector (docs/CONVENTIONS.md "The lag detector"), defaults resolved.
    bool antilag = false;
    double antilag_gamma = 2.0;      // gamma_a
    double antilag_threshold = 0.5;  // T_a
    // 0.6 the blur bound (docs/CONVENTIONS.md "The blur bound"): B in px^2, 0 = off.
    double blur_bound = 0.0;
    // 0.7 the view-dependent history (docs/CONVENTIONS.md "The view-dependent history"): alpha in radians, 0 = off.
    double view_lobe = 0.0;
    // 0.9 the residual (docs/CONVENTIONS.md "The residual"): the channel filters s - b, b its fallback.
    bool residual = false;
    // 0.12 the deviation gate (docs/CONVENTIONS.md "The deviation gate"): kappa, 0 = off.
    double gate_kappa = 0.0;
    TableOptions options;
};

struct Params {
    int width, height;
    rrc_depth_mode mode;
    double near_plane, far_plane;  // as the host passed them (floats)
    double background_threshold;   // LINEAR
    rrc_depth_format format;
    double epsilon_scale;
    double epsilon;  // > 0: absolute epsilon (NDC tests)
    double tau;
    rrc_reprojection source;
    double motion_scale[2];
    bool nocache;
    // docs/CONVENTIONS.md "Which test": the ADAPTIVE test applies (ADAPTIVE
    // asked for, or the 0.2 default with no tolerance set; not plain MOTION).
    bool adaptive;
    bool object_id;  // frames carry object ids: every weighted tap must match
    // The shading cache (docs/CONVENTIONS.md, "The shading cache").
    rrc_refresh_policy refresh_policy;
    unsigned refresh_period;    // n (1 without a policy)
    unsigned refresh_tiles[2];  // TILED {gx, gy}, {0, 0} resolved to {n, 1}
    unsigned max_lifetime;      // 0: none
    std::vector<ChannelParams> channels;
    bool has_reuse() const {
        for (const ChannelParams& c : channels)
            if (c.blend == RRC_BLEND_REUSE) return true;
        return false;
    }

    // Plain MOTION on NDC depth compares linearised depths relatively.
    bool relative_test() const { return mode == RRC_DEPTH_MODE_LINEAR || source == RRC_REPROJECTION_MOTION; }
    bool linearise() const { return mode != RRC_DEPTH_MODE_LINEAR && source == RRC_REPROJECTION_MOTION; }
};

Params resolve(const rrc_context_desc& ctx);

// Background rule applied to any depth value (current pixel or previous tap).
bool is_background(const Params& p, double depth);
// The current pixel's depth is unusable (non-finite other than LINEAR's +inf
// background, or outside the mode's range).  Checked before is_background.
bool is_invalid_depth(const Params& p, double depth);

// Linear view depth from NDC z with the context's near/far planes.
Bounded linearise(const Params& p, Bounded z);

// Tolerance at expected depth e (see rrc_reference.h epsilon_for).
double epsilon_at(const Params& p, double e);

}  // namespace rrc_ref

#endif
