// The configurations a sweep measures: brute force at k samples a frame, and
// rrc at k samples a frame with each lambda, blend and history filter; one
// rrc context per (application, configuration), so each row's rrc time is
// that channel's alone.
#pragma once

#include "channel_presets.h"
#include "sweep_options.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rrc_sweep {

/** An application: one of rrc-sample's signals. */
struct App {
    uint32_t signal;   // rrc_sample::Signal bit
    const char* name;  // pcf, env, soft
};
std::vector<App> apps_of(uint32_t signals);

struct RrcConfig {
    App app;
    rrc_sample::ChannelSettings channel;
};

/** One seed run: k samples a frame with one PCF pattern, every configuration fed from the same signals. */
struct RrcRun {
    int k = 1;
    uint32_t pattern = 0;  // 0 uniform disk, 1 the paper's rotated Poisson pattern (pcf rows only)
    std::vector<RrcConfig> configs;
};

struct BruteConfig {
    App app;
    int k = 1;
    uint32_t pattern = 0;
};

/** The rrc runs: every k of --taps with every configuration, then (pcf, --rotated) k = 4
 *  with the rotated pattern, fixed and age-aware, bilinear. */
std::vector<RrcRun> rrc_runs(const SweepOptions& o, uint32_t signals);
/** Brute force: every k of --brute-taps per application; pcf's rotated pattern at 4, 16 and 64 taps. */
std::vector<BruteConfig> brute_configs(const SweepOptions& o, uint32_t signals);

/** The CSV's spellings: fixed, age-aware, running-mean; bilinear, catmull-rom. */
const char* blend_label(rrc_blend blend);
const char* filter_label(rrc_history_filter filter);
/** The filter with the finishing steps and cures a row adds ("bilinear+rectify", "bilinear+fill8",
 *  "bilinear+rectify+antilag", "bilinear+rectify+blur0.5"): the sweep's filter column. */
std::string filter_label(const rrc_sample::ChannelSettings& c);
/** The lag detector's rows (--no-antilag drops them): gamma_a and T, the best of docs/measurements/PERFORMANCE.md,
 *  "The lag detector (0.5): what it buys, measured" (pcf at 1024x640, lambda 0.9). */
constexpr float kSweepAntilagGamma = 1.0f;
constexpr float kSweepAntilagThreshold = 0.25f;
/** The blur bound's rows (--no-blur-bound drops them): B in px^2, the best of docs/measurements/PERFORMANCE.md,
 *  "The blur bound: what it buys, measured" (pcf bilinear and soft at 256x160). */
constexpr float kSweepBlurBound = 0.5f;
/** The view lobe's rows (--no-view-lobe drops them; env only): alpha in radians, the lobe whose age
 *  cap is 1 on the mirror sphere under the default camera (docs/measurements/PERFORMANCE.md, "The view lobe in
 *  the kernel (0.7), measured"). */
constexpr float kSweepViewLobe = 0.0245f;
/** The taps the rotated pattern's fixed point set has (its brute force is rotations of it). */
constexpr int kRotatedBaseTaps = 4;

}  // namespace rrc_sweep
