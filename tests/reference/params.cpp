#include "params.h"

#include <cmath>

#include "rrc_reference.h"

namespace rrc_ref {

namespace {

// CONVENTIONS "fp16 history": a channel asking for fp16 keeps it only while
// its lambda_eff stays at or below RRC_FP16_MAX_LAMBDA.  lambda_eff never
// decreases with the age n and the age saturates at the cap, so its largest
// value is the one at n = cap: n/(n+1) for the running mean, that or lambda,
// whichever is smaller, for the age-aware blend, lambda for the fixed one.
// REUSE never blends: nothing to stall.
bool stalls_in_fp16(double lambda, rrc_blend blend, unsigned cap) {
    if (blend == RRC_BLEND_REUSE) return false;
    const double at_cap = static_cast<double>(cap) / (static_cast<double>(cap) + 1.0);
    double largest = lambda;
    if (blend == RRC_BLEND_RUNNING_MEAN) largest = at_cap;
    if (blend == RRC_BLEND_AGE_AWARE && at_cap < lambda) largest = at_cap;
    return largest > RRC_FP16_MAX_LAMBDA;
}

}  // namespace

Params resolve(const rrc_context_desc& ctx) {
    Params p{};
    p.width = static_cast<int>(ctx.width);
    p.height = static_cast<int>(ctx.height);
    p.mode = ctx.depth_mode;
    p.near_plane = ctx.near_plane;
    p.far_plane = ctx.far_plane;
    p.background_threshold = ctx.background_threshold != 0.0f ? ctx.background_threshold : 1e10;
    p.format = ctx.depth_format;
    p.epsilon_scale = ctx.epsilon_scale != 0.0f ? ctx.epsilon_scale : ctx.depth_format == RRC_DEPTH_FORMAT_FLOAT32 ? 4.0 : 1.0;
    p.epsilon = ctx.epsilon;
    p.tau = ctx.tau != 0.0f ? ctx.tau : 0.01;
    p.source = ctx.reprojection;
    bool no_scale = ctx.motion_scale[0] == 0.0f && ctx.motion_scale[1] == 0.0f;
    p.motion_scale[0] = no_scale ? 1.0 : ctx.motion_scale[0];
    p.motion_scale[1] = no_scale ? 1.0 : ctx.motion_scale[1];
    p.nocache = ctx.use_nocache_mask != 0;
    p.object_id = ctx.use_object_id != 0;
    p.refresh_policy = ctx.refresh_policy;
    p.refresh_period = ctx.refresh_policy != RRC_REFRESH_NONE ? ctx.refresh_period : 1u;
    p.refresh_tiles[0] = ctx.refresh_tiles[0];
    p.refresh_tiles[1] = ctx.refresh_tiles[1];
    if (p.refresh_tiles[0] == 0 && p.refresh_tiles[1] == 0) p.refresh_tiles[0] = p.refresh_period, p.refresh_tiles[1] = 1;
    p.max_lifetime = ctx.max_lifetime;
    const bool tolerance = ctx.epsilon_scale != 0.0f || ctx.epsilon != 0.0f || ctx.tau != 0.0f;
    const bool asked = ctx.depth_test == RRC_DEPTH_TEST_ADAPTIVE ||
                       (ctx.depth_test == RRC_DEPTH_TEST_DEFAULT && !tolerance && ctx.api_version >= RRC_MAKE_VERSION(0, 2, 0));
    p.adaptive = asked && p.source != RRC_REPROJECTION_MOTION;  // plain MOTION has no exact expected depth
    for (uint32_t c = 0; c < ctx.channel_count; ++c) {
        const rrc_channel_desc& d = ctx.channels[c];
        const unsigned cap = d.age_cap != 0 ? d.age_cap : 255u;
        ChannelParams ch{
            d.components,     d.precision == RRC_HISTORY_FP16 && !stalls_in_fp16(d.lambda, d.blend, cap), d.lambda, d.blend, d.filter, cap,
            d.confidence != 0};
        // 0.4: a zero member is the feature's default (or off).
        ch.rectify = d.rectify != 0;
        ch.rectify_gamma = d.rectify_gamma != 0.0f ? d.rectify_gamma : RRC_DEFAULT_RECTIFY_GAMMA;
        const double sigma = d.blur_sigma != 0.0f ? d.blur_sigma : RRC_DEFAULT_BLUR_SIGMA;
        ch.blur_g = sigma * sigma / 2.0;
        ch.fill_age = d.fill_age;
        ch.fill_radius = d.fill_radius != 0 ? static_cast<int>(d.fill_radius) : static_cast<int>(RRC_DEFAULT_FILL_RADIUS);
        ch.fill_tau = d.fill_depth_tolerance != 0.0f ? d.fill_depth_tolerance : RRC_DEFAULT_FILL_DEPTH_TOLERANCE;
        ch.fill_prior = d.fill_prior;
        ch.antilag = d.antilag != 0;
        ch.antilag_gamma = d.antilag_gamma != 0.0f ? d.antilag_gamma : RRC_DEFAULT_ANTILAG_GAMMA;
        ch.antilag_threshold = d.antilag_threshold != 0.0f ? d.antilag_threshold : RRC_DEFAULT_ANTILAG_THRESHOLD;
        ch.blur_bound = d.blur_bound;
        ch.view_lobe = d.view_lobe;
        ch.residual = d.residual != 0;
        ch.gate_kappa = d.gate_kappa;
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, ...) \
    ch.options.member = d.member != 0 ? (double)d.member : (double)(dflt);
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
        p.channels.push_back(ch);
    }
    return p;
}

bool is_background(const Params& p, double d) {
    switch (p.mode) {
        case RRC_DEPTH_MODE_STANDARD: return d >= 1.0;
        case RRC_DEPTH_MODE_REVERSED: return d <= 0.0;
        default: return d >= p.background_threshold;  // also +inf
    }
}

bool is_invalid_depth(const Params& p, double d) {
    switch (p.mode) {
        case RRC_DEPTH_MODE_STANDARD: return !std::isfinite(d) || d < 0.0;
        case RRC_DEPTH_MODE_REVERSED: return !std::isfinite(d) || d > 1.0;
        default: return std::isnan(d) || d == -INFINITY || d <= 0.0;
    }
}

Bounded linearise(const Params& p, Bounded z) {
    Bounded n = exact(p.near_plane), f = exact(p.far_plane), one = exact(1.0);
    if (std::isinf(p.far_plane)) {  // limits of the formulas below
        return p.mode == RRC_DEPTH_MODE_REVERSED ? n / z : n / (one - z);
    }
    if (p.mode == RRC_DEPTH_MODE_REVERSED) return n * f / (n + z * (f - n));
    return n * f / (f - z * (f - n));
}

double ulp_fp32(double v) {
    float f = static_cast<float>(v);
    double a = std::fabs(static_cast<double>(f));
    if (!(a >= FLT_MIN)) return 0x1p-149;  // zero, fp32 denormal (and NaN)
    if (std::isinf(v)) return NAN;         // no tolerance at an infinite depth: the test fails
    // Beyond the fp32 range the formula is applied to v itself (the kernel's
    // own overflow is covered by the error bound, not here).
    return std::ldexp(1.0, std::ilogb(std::isinf(a) ? v : a) - 23);
}

double epsilon_at(const Params& p, double e) {
    if (p.relative_test()) return p.tau * e;
    if (p.epsilon > 0.0) return p.epsilon;
    switch (p.format) {
        case RRC_DEPTH_FORMAT_UNORM16: return p.epsilon_scale / 65535.0;
        case RRC_DEPTH_FORMAT_UNORM24: return p.epsilon_scale / 16777215.0;
        default: return p.epsilon_scale * ulp_fp32(e);
    }
}

double epsilon_for(const rrc_context_desc& ctx, double expected_depth) { return epsilon_at(resolve(ctx), expected_depth); }

}  // namespace rrc_ref
