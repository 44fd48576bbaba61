#include "config.h"

namespace rrc_bench {
namespace {

Config base() {
    Config c;
    c.name = "base";
    c.factor = "base";
    return c;
}

Config vary(const std::string& name, const std::string& factor) {
    Config c = base();
    c.name = name;
    c.factor = factor;
    return c;
}

}  // namespace

std::vector<Config> full_sweep() {
    std::vector<Config> all{base()};
    const uint32_t sizes[][2] = {{256, 160}, {640, 360}, {1280, 720}, {2560, 1440}, {3840, 2160}};
    for (const auto& s : sizes) {
        Config c = vary("res_" + std::to_string(s[0]) + "x" + std::to_string(s[1]), "resolution");
        c.width = s[0];
        c.height = s[1];
        all.push_back(c);
    }
    for (uint32_t n = 1; n <= 4; ++n)
        for (uint32_t comps : {1u, 4u}) {
            if (n == 1 && comps == 1) continue;  // that is base
            Config c = vary("ch_" + std::to_string(n) + "x" + std::to_string(comps), "channels");
            ChannelConfig ch;
            ch.components = comps;
            c.channels.assign(n, ch);
            all.push_back(c);
        }
    {
        Config c = vary("fp32", "precision");
        c.channels[0].precision = RRC_HISTORY_FP32;
        all.push_back(c);
    }
    const std::pair<const char*, rrc_reprojection> sources[] = {
        {"src_motion", RRC_REPROJECTION_MOTION}, {"src_motion_depth", RRC_REPROJECTION_MOTION_DEPTH}, {"src_camera", RRC_REPROJECTION_CAMERA}};
    for (const auto& s : sources) {
        Config c = vary(s.first, "source");
        c.source = s.second;
        all.push_back(c);
    }
    const std::pair<const char*, rrc_history_filter> filters[] = {{"filter_nearest", RRC_HISTORY_FILTER_NEAREST},
                                                                  {"filter_bilinear", RRC_HISTORY_FILTER_BILINEAR},
                                                                  {"filter_catmull_rom", RRC_HISTORY_FILTER_CATMULL_ROM},
                                                                  {"filter_gaussian", RRC_HISTORY_FILTER_GAUSSIAN}};
    for (const auto& f : filters) {
        Config c = vary(f.first, "filter");
        c.channels[0].filter = f.second;
        all.push_back(c);
    }
    // One switch away from base each.
    const struct {
        const char* name;
        const char* factor;
        void (*set)(Config&);
    } switches[] = {
        {"confidence", "confidence", [](Config& c) { c.channels[0].confidence = true; }},
        {"nocache", "nocache", [](Config& c) { c.nocache = true; }},
        {"rectify", "rectify", [](Config& c) { c.channels[0].rectify = true; }},
        // A lobe the poses' 6 cm turn (up to 0.011 rad at 5 m) caps at age 1 or 2: the cap acts on every hit.
        {"view_lobe", "view_lobe", [](Config& c) { c.channels[0].view_lobe = 0.02f; }},
        {"residual", "residual", [](Config& c) { c.channels[0].residual = true; }},
        {"fill", "fill", [](Config& c) { c.channels[0].fill_age = 8; }},
        {"fill_r1", "fill", [](Config& c) { c.channels[0].fill_age = 8, c.channels[0].fill_radius = 1; }},
        {"fill_r4", "fill", [](Config& c) { c.channels[0].fill_age = 8, c.channels[0].fill_radius = 4; }},
        // kappa 4, docs/guide/offline.md's setting for cleaner frames.
        {"gate", "gate", [](Config& c) { c.channels[0].gate_kappa = 4.0f; }},
        {"object_id", "object_id", [](Config& c) { c.object_id = true; }},
        {"depth_fixed", "depth_test", [](Config& c) { c.depth_test = RRC_DEPTH_TEST_FIXED; }},
        {"sampled_inputs", "inputs", [](Config& c) { c.sampled_inputs = true; }},
        {"standalone", "path", [](Config& c) { c.standalone = true; }},
        {"cache_1x4", "shading_cache", [](Config& c) {
             c.shading_cache = Config::Cache::Split;
             c.channels[0].components = 4;
         }},
        {"cache_1x4_copy", "shading_cache", [](Config& c) {
             c.shading_cache = Config::Cache::Split;
             c.split_outputs = false;
             c.channels[0].components = 4;
         }},
        {"cache_1x4_fused", "shading_cache", [](Config& c) {
             c.shading_cache = Config::Cache::Fused;
             c.channels[0].components = 4;
         }},
        {"cache_1x4_classify_fused", "shading_cache", [](Config& c) {
             c.shading_cache = Config::Cache::ClassifyFused;
             c.channels[0].components = 4;
         }},
    };
    for (const auto& sw : switches) {
        Config c = vary(sw.name, sw.factor);
        sw.set(c);
        all.push_back(c);
    }
    // The fill at a stated young fraction: the fill works on young pixels
    // only, so its cost is set against its twin without the fill at the same
    // nocache share (young12), round by round (docs/measurements/PERFORMANCE.md, "Targets").
    // young12_fill_residual: the fill with the residual (rrc-sample's pcf preset);
    // young12_fill_gate: the fill weighed by the deviation gate's state;
    // young12_fill_3x1 against young12_3x1: three channels with a fill (rrc-sample's three).
    const struct {
        const char* name;
        uint32_t fill_age, fill_radius;
        bool residual;
        float gate_kappa;
        uint32_t channels;
    } young[] = {{"young12", 0, 0, false, 0.0f, 1},
                 {"young12_fill", kYoungAge, 0, false, 0.0f, 1},
                 {"young12_fill_r1", kYoungAge, 1, false, 0.0f, 1},
                 {"young12_fill_r4", kYoungAge, 4, false, 0.0f, 1},
                 {"young12_fill_residual", kYoungAge, 0, true, 0.0f, 1},
                 {"young12_fill_gate", kYoungAge, 0, false, 4.0f, 1},
                 {"young12_3x1", 0, 0, false, 0.0f, 3},
                 {"young12_fill_3x1", kYoungAge, 0, false, 0.0f, 3}};
    // rrc-sample's three presets as a host with a base renders them (rrc_channel_preset with
    // RRC_PRESET_FLAG_BASE: each has the residual): what a pixel moves with each.
    const struct {
        const char* name;
        rrc_preset preset;
        uint32_t components;
    } presets[] = {{"preset_pcf", RRC_PRESET_PCF_SHADOWS, 1}, {"preset_env", RRC_PRESET_ENV_BUMP, 4}, {"preset_soft", RRC_PRESET_SOFT_SHADOWS, 1}};
    for (const auto& p : presets) {
        Config c = vary(p.name, "preset");
        c.channels[0].preset = p.preset;
        c.channels[0].components = p.components;
        c.channels[0].residual = true;
        all.push_back(c);
    }
    for (const auto& y : young) {
        Config c = vary(y.name, "young");
        c.nocache = true;
        c.nocache_share = kYoungNocacheShare;
        c.young = true;
        c.channels[0].fill_age = y.fill_age;
        c.channels[0].fill_radius = y.fill_radius;
        c.channels[0].residual = y.residual;
        c.channels[0].gate_kappa = y.gate_kappa;
        c.channels.assign(y.channels, c.channels[0]);
        all.push_back(c);
    }
    return all;
}

std::vector<std::string> short_sweep_names() {
    // depth_fixed, cache_1x4_fused and young12 are the denominators of the
    // ADAPTIVE, shading cache and fill targets (docs/measurements/PERFORMANCE.md, "Targets").
    return {"base", "ch_3x1", "src_camera", "src_motion", "res_256x160", "res_1280x720", "res_3840x2160", "sampled_inputs",
            "standalone", "depth_fixed", "cache_1x4", "cache_1x4_fused", "cache_1x4_classify_fused", "young12", "young12_fill"};
}

std::string channels_text(const Config& c) {
    std::string s;
    for (const ChannelConfig& ch : c.channels) {
        if (!s.empty()) s += "+";
        s += std::to_string(ch.components) + (ch.precision == RRC_HISTORY_FP32 ? "f32" : "f16");
        if (ch.confidence) s += "c";
        if (ch.rectify) s += "r";
        if (ch.fill_age) s += "F";
        if (ch.view_lobe > 0.0f) s += "V";
        if (ch.residual) s += "B";
        if (ch.gate_kappa > 0.0f) s += "G";
        if (ch.preset == RRC_PRESET_PCF_SHADOWS) s += "[pcf]";
        if (ch.preset == RRC_PRESET_ENV_BUMP) s += "[env]";
        if (ch.preset == RRC_PRESET_SOFT_SHADOWS) s += "[soft]";
    }
    return s;
}

}  // namespace rrc_bench
