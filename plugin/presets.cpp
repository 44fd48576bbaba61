// rrc_channel_preset and rrc_context_preset (rrc.h, "Presets"): each
// application's best measured setting, per tuning version.  The values and
// what each buys: docs/guide/ (one guide per application) and
// docs/reference/presets.md, which a test compares with this table.
#include "presets.h"

#include "error.h"
#include "struct_reader.h"  // write_member

#include <cstddef>
#include <cstring>

namespace rrc {
namespace {

constexpr uint32_t kFirstTuning = RRC_MAKE_VERSION(0, 11, 0);

constexpr PresetContext kNoContext{};
constexpr PresetContext kOfflineContext{true, RRC_DEPTH_MODE_LINEAR, RRC_REPROJECTION_MOTION, 0.04f};
constexpr PresetContext kCacheContext{false, 0, 0, 0.0f, true, RRC_REFRESH_TILED, 4, {0, 0}, 8};  // {0, 0}: {4, 1}, vertical strips

// One row per preset and variant, per tuning; a re-tune appends rows under
// its own version and keeps these (rrc.h, "Presets").
//  lambda, blend, filter, age_cap, fill_age, fill_radius, fill_prior, rectify, antilag, antilag_gamma, antilag_threshold,
//  blur_bound, view_lobe, residual
constexpr PresetRow kTunings[] = {
    {kFirstTuning, RRC_PRESET_PCF_SHADOWS, true,
     {0.9f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0, 4, 0, 0.0f, 0, 0, 0.0f, 0.0f, 0.0f, 0.0f, 1}, kNoContext},
    {kFirstTuning, RRC_PRESET_PCF_SHADOWS, false,
     {0.9f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0, 4, 1, 0.0f, 0, 1, 0.25f, 0.25f, 0.25f, 0.0f, 0}, kNoContext},
    {kFirstTuning, RRC_PRESET_ENV_BUMP, true,
     {0.9f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0, 2, 0, 0.0f, 0, 0, 0.0f, 0.0f, 0.0f, 0.08f, 1}, kNoContext},
    {kFirstTuning, RRC_PRESET_ENV_BUMP, false,
     {0.8f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0, 2, 0, 0.0f, 0, 0, 0.0f, 0.0f, 0.0f, 0.05f, 0}, kNoContext},
    {kFirstTuning, RRC_PRESET_SOFT_SHADOWS, true,
     {0.95f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_CATMULL_ROM, 64, 8, 0, 4.0f, 0, 0, 0.0f, 0.0f, 0.0f, 0.0f, 1}, kNoContext},
    {kFirstTuning, RRC_PRESET_SOFT_SHADOWS, false,
     {0.8f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 64, 8, 0, 0.0f, 0, 0, 0.0f, 0.0f, 0.5f, 0.0f, 0}, kNoContext},
    {kFirstTuning, RRC_PRESET_SHADING_CACHE, false,
     {0.0f, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_BILINEAR, 0, 0, 0, 0.0f, 0, 0, 0.0f, 0.0f, 0.0f, 0.0f, 0}, kCacheContext},
    {kFirstTuning, RRC_PRESET_OFFLINE, false,
     {0.85f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0, 4, 0, 0.0f, 1, 0, 0.0f, 0.0f, 0.0f, 0.0f, 0}, kOfflineContext},
};

bool takes_base(rrc_preset p) { return p == RRC_PRESET_PCF_SHADOWS || p == RRC_PRESET_ENV_BUMP || p == RRC_PRESET_SOFT_SHADOWS; }

uint32_t minor_of(uint32_t v) { return RRC_MAKE_VERSION(RRC_VERSION_MAJOR(v), RRC_VERSION_MINOR(v), 0); }

}  // namespace

const PresetRow* find_preset(rrc_preset preset, uint32_t flags, uint32_t tuning) {
    if (preset < RRC_PRESET_PCF_SHADOWS || preset > RRC_PRESET_OFFLINE)
        fail(RRC_ERROR_INVALID_ARGUMENT, "preset is %u, not an RRC_PRESET_* value", (unsigned)preset);
    if (flags & ~RRC_PRESET_FLAG_BASE) fail(RRC_ERROR_INVALID_ARGUMENT, "flags is 0x%x: the only flag is RRC_PRESET_FLAG_BASE", flags);
    const bool base = (flags & RRC_PRESET_FLAG_BASE) != 0;
    if (base && !takes_base(preset))
        fail(RRC_ERROR_INVALID_ARGUMENT, "RRC_PRESET_FLAG_BASE: only the PCF_SHADOWS, ENV_BUMP and SOFT_SHADOWS presets have a base");
    const uint32_t library = minor_of(RRC_API_VERSION);
    uint32_t want = tuning ? minor_of(tuning) : library;
    if (RRC_VERSION_MAJOR(want) != RRC_VERSION_MAJOR(library) || want > library)
        fail(RRC_ERROR_UNSUPPORTED, "tuning %u.%u is newer than this library (%u.%u): its presets' values are unknown here",
             RRC_VERSION_MAJOR(want), RRC_VERSION_MINOR(want), RRC_VERSION_MAJOR(library), RRC_VERSION_MINOR(library));
    if (want < kFirstTuning) want = kFirstTuning;
    const PresetRow* best = nullptr;
    for (const PresetRow& t : kTunings)
        if (t.preset == preset && t.base == base && t.version <= want && (!best || t.version > best->version)) best = &t;
    if (!best) fail(RRC_ERROR_INVALID_ARGUMENT, "no tuning of preset %u", (unsigned)preset);  // every preset has a 0.11 row
    return best;
}

void write_channel_preset(const PresetRow& row, rrc_channel_desc* caller) {
    using C = rrc_channel_desc;
    const PresetChannel& v = row.channel;
    write_member(caller, offsetof(C, lambda), v.lambda);
    write_member(caller, offsetof(C, blend), v.blend);
    write_member(caller, offsetof(C, filter), v.filter);
    write_member(caller, offsetof(C, age_cap), v.age_cap);
    write_member(caller, offsetof(C, rectify), v.rectify);
    write_member(caller, offsetof(C, rectify_gamma), 0.0f);
    write_member(caller, offsetof(C, blur_sigma), 0.0f);
    write_member(caller, offsetof(C, fill_age), v.fill_age);
    write_member(caller, offsetof(C, fill_radius), v.fill_radius);
    write_member(caller, offsetof(C, fill_depth_tolerance), 0.0f);
    write_member(caller, offsetof(C, fill_prior), v.fill_prior);
    write_member(caller, offsetof(C, antilag), v.antilag);
    write_member(caller, offsetof(C, antilag_gamma), v.antilag_gamma);
    write_member(caller, offsetof(C, antilag_threshold), v.antilag_threshold);
    write_member(caller, offsetof(C, blur_bound), v.blur_bound);
    write_member(caller, offsetof(C, view_lobe), v.view_lobe);
    write_member(caller, offsetof(C, residual), v.residual);
    write_member(caller, offsetof(C, gate_kappa), v.gate_kappa);
}

void write_context_preset(const PresetRow& row, const rrc_context_desc& d, rrc_context_desc* caller) {
    using D = rrc_context_desc;
    const PresetContext& v = row.context;
    if (v.fixes_geometry) {
        if (d.width == 0 || d.height == 0)
            fail(RRC_ERROR_INVALID_ARGUMENT, "context.width/height is %ux%u: the OFFLINE preset's motion_scale {1/W, -1/H} needs them set",
                 d.width, d.height);
        const float scale[2] = {static_cast<float>(1.0 / d.width), static_cast<float>(-1.0 / d.height)};
        write_member(caller, offsetof(D, depth_mode), v.depth_mode);
        write_member(caller, offsetof(D, reprojection), v.reprojection);
        write_member(caller, offsetof(D, motion_scale), scale);
        write_member(caller, offsetof(D, tau), v.tau);
        write_member(caller, offsetof(D, epsilon_scale), 0.0f);
        write_member(caller, offsetof(D, epsilon), 0.0f);
        write_member(caller, offsetof(D, depth_test), (rrc_depth_test)RRC_DEPTH_TEST_FIXED);
    }
    if (v.fixes_refresh) {
        write_member(caller, offsetof(D, refresh_policy), v.refresh_policy);
        write_member(caller, offsetof(D, refresh_period), v.refresh_period);
        write_member(caller, offsetof(D, refresh_tiles), v.refresh_tiles);
        write_member(caller, offsetof(D, max_lifetime), v.max_lifetime);
    }
}

}  // namespace rrc
