// One benchmark configuration and the sweep around the base: every factor of
// the sweep (docs/measurements/PERFORMANCE.md, "Full sweep") is varied alone, so a row's change against `base` is that
// factor's cost.  The short default run is a subset that still covers the
// targets of docs/measurements/PERFORMANCE.md (channels, sources, linearity, standalone).
#pragma once

#include <rrc/rrc.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rrc_bench {

struct ChannelConfig {
    uint32_t components = 1;                          // 1 or 4
    rrc_history_precision precision = RRC_HISTORY_FP16;
    rrc_history_filter filter = 0;                    // 0: the library's default
    bool confidence = false;
    bool rectify = false;   // 0.4: history rectification (reads 8 more samples; no byte the roof counts)
    uint32_t fill_age = 0;  // 0.4: the spatial fill, no fallback (a second dispatch; no byte the roof counts)
    uint32_t fill_radius = 0;  // 0: the library's default
    float view_lobe = 0.0f;    // 0.7: the view-dependent history's lobe, radians (the view turn a pixel; no byte the roof counts)
    bool residual = false;     // 0.9: the residual against a base image (4 bytes a pixel more read, which the roof does not count)
    float gate_kappa = 0.0f;   // 0.12: the deviation gate (its state is the library's own; no byte the roof counts)
    // Non-zero: the channel is rrc_channel_preset(preset, RRC_PRESET_FLAG_BASE) over its components and
    // precision (the options above are ignored but `residual`, which every base preset has).
    rrc_preset preset = 0;
};

struct Config {
    std::string name;    // unique, what --config takes
    std::string factor;  // the factor varied from base ("base" for base itself)
    uint32_t width = 1920, height = 1080;
    std::vector<ChannelConfig> channels{ChannelConfig{}};
    rrc_reprojection source = RRC_REPROJECTION_PREV_CLIP;
    bool nocache = false;
    // The share of pixels the nocache mask marks (with nocache): 1 % by
    // default.  Those pixels miss every frame (age 1), so the share sets how
    // many pixels are young (age < fill_age): the fill rows' workload
    // (docs/measurements/PERFORMANCE.md, "What is timed").
    float nocache_share = 0.01f;
    // A row of the fill's cost at a stated young fraction: --nocache-share
    // sets its nocache_share.
    bool young = false;
    bool object_id = false;
    rrc_depth_test depth_test = 0;  // 0: the library's default (ADAPTIVE)
    bool standalone = false;        // also time the standalone path (CPU arrays)
    // The host's input images have STORAGE usage in the kernel's formats, so
    // every configuration passes rrc_vulkan_frame_desc.storage_inputs (the
    // roof reads them the same way) but MOTION, whose RG32F vectors the
    // kernel only samples; sampled_inputs times the sampler path that any
    // host's images allow.
    bool sampled_inputs = false;
    // The shading cache: the channels are REUSE with TILED refresh (n = 4,
    // 2x2 tiles); Fused runs them through rrc_vulkan_record_frame, Split runs
    // classify + resolve (no host shader in between: the samples image holds
    // values already).  The roof is the same copy: the split moves no byte the
    // API implies beyond the fused frame's but the quad list (not counted).
    // ClassifyFused: classify, then the fused frame (a diagnostic: classify's
    // cost is this row's time less Fused's; classify alone never advances history).
    enum class Cache { Off, Fused, Split, ClassifyFused } shading_cache = Cache::Off;
    // A frame is one rrc_vulkan_record_frame (no classify): its statistics frame also counts the
    // image operations (rrc_vulkan_frame_desc.count_io, which classify and resolve ignore).
    bool records_frame_only() const { return shading_cache == Cache::Off || shading_cache == Cache::Fused; }
    // Split: classify and resolve share the host's outputs (rrc_vulkan_frame_desc.split_outputs);
    // false: resolve copies every pixel into them (the 0.3/0.4 behaviour).
    bool split_outputs = true;
};

/** The age below which a pixel is young: the fill rows' fill_age; the
 *  bench counts young pixels against it in every row. */
constexpr uint32_t kYoungAge = 8;
/** The young rows' nocache share: chosen so that about 12 % of all pixels
 *  (surface pixels of age < kYoungAge over the frame's pixels) are young at
 *  1080p (docs/measurements/PERFORMANCE.md, "What is timed"). */
constexpr float kYoungNocacheShare = 0.08f;

/** Every configuration of --full, base first. */
std::vector<Config> full_sweep();
/** The names the short default run takes from full_sweep(). */
std::vector<std::string> short_sweep_names();
/** "1x fp16 r" style summary of the channels. */
std::string channels_text(const Config& c);

}  // namespace rrc_bench
