// The context's configuration with every default applied: what the
// validated rrc_context_desc means, in one place.
#pragma once

#include <rrc/rrc.h>
#include <rrc_kernel_interface.h>  // RRC_EPS_* (compute/)

#include <array>
#include <string>
#include <vector>

namespace rrc {

struct ChannelConfig {
    std::string name;
    // One member a row of compute/rrc_channel_options.def, as the caller set
    // it with its "0 = default" resolved (plugin/validation.cpp).
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, ...) ctype member = dflt;
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
    // The history actually kept in fp16: asked for, and not promoted to fp32
    // above RRC_FP16_MAX_LAMBDA (docs/CONVENTIONS.md, "The recursive filter").
    bool fp16 = true;
    // The kernel caps ages only where the fetch blurs: BILINEAR and GAUSSIAN
    // (NEAREST and CATMULL_ROM have b = 0, so their code is compiled out).
    bool blur_bound_active() const {
        return blur_bound > 0.0f && (filter == RRC_HISTORY_FILTER_BILINEAR || filter == RRC_HISTORY_FILTER_GAUSSIAN);
    }
    bool reuse() const { return blend == RRC_BLEND_REUSE; }
    bool fill() const { return fill_age != 0; }
    // Frames carry a fallback: the fill's prior, or the residual's base.
    bool fallback() const { return fill_prior > 0.0f || residual; }
    // The displayed value differs from the history's: the fill, or the residual's added base.
    bool displayed() const { return fill() || residual; }
};

// How the kernel's epsilon is formed: the value of EPS_KIND in
// compute/rrc_reproject.glsl (RRC_EPS_* of compute/rrc_kernel_interface.h).
enum class EpsilonKind : uint32_t { Absolute = RRC_EPS_ABSOLUTE, Ulp = RRC_EPS_ULP, Relative = RRC_EPS_RELATIVE };

struct ContextConfig {
    uint32_t width = 0, height = 0;
    rrc_depth_mode depth_mode = RRC_DEPTH_MODE_STANDARD;
    rrc_depth_format depth_format = RRC_DEPTH_FORMAT_FLOAT32;
    float near_plane = 0, far_plane = 0;
    float background_threshold = RRC_DEFAULT_BACKGROUND_THRESHOLD;
    rrc_reprojection reprojection = RRC_REPROJECTION_PREV_CLIP;
    std::array<float, 2> motion_scale{1.0f, 1.0f};
    EpsilonKind epsilon_kind = EpsilonKind::Ulp;
    float epsilon_value = RRC_DEFAULT_EPSILON_SCALE_FLOAT32;  // absolute epsilon, ulp scale, or tau (by kind)
    rrc_depth_test depth_test = RRC_DEPTH_TEST_FIXED;         // resolved: ADAPTIVE or FIXED, never DEFAULT
    // The kernel's ADAPTIVE constant: the ADAPTIVE test, for every source with
    // an exact expected depth (plain MOTION's linearised test is tau * d under both).
    bool adaptive = false;
    bool use_object_id = false;
    bool use_nocache = false;
    // The shading cache (docs/CONVENTIONS.md, "The shading cache").
    rrc_refresh_policy refresh_policy = RRC_REFRESH_NONE;
    uint32_t refresh_period = 1;              // n (1 without a policy)
    uint32_t refresh_tiles[2] = {1, 1};       // TILED: {gx, gy}, gx * gy = n
    uint32_t max_lifetime = 0;                // 0: none
    uint32_t view_count = 1;
    uint32_t fill_mask() const {  // bit c: channel c has a spatial fill
        uint32_t m = 0;
        for (size_t i = 0; i < channels.size(); ++i) m |= channels[i].fill() ? 1u << i : 0u;
        return m;
    }
    uint32_t displayed_mask() const {  // bit c: channel c's displayed value is not its history (ChannelConfig::displayed)
        uint32_t m = 0;
        for (size_t i = 0; i < channels.size(); ++i) m |= channels[i].displayed() ? 1u << i : 0u;
        return m;
    }
    // A channel has a view lobe: every frame carries the camera (the view buffer, rrc_kernel_interface.h).
    bool view_lobe() const {
        for (const ChannelConfig& c : channels)
            if (c.view_lobe > 0.0f) return true;
        return false;
    }
    uint32_t reuse_mask() const {             // bit c: channel c is REUSE
        uint32_t m = 0;
        for (size_t i = 0; i < channels.size(); ++i) m |= channels[i].reuse() ? 1u << i : 0u;
        return m;
    }
    std::vector<ChannelConfig> channels;
    std::string device_name;  // empty: automatic choice
    bool validation = false;
    rrc_log_fn log = nullptr;
    void* log_user = nullptr;
};

// Validates desc (throws rrc::Error naming the field) and applies defaults.
ContextConfig resolve_context_desc(const rrc_context_desc* desc);

}  // namespace rrc
