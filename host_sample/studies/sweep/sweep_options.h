// rrc-sweep's command line: which configurations, how many seeds and frames.
#pragma once

#include "options.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace rrc_sweep {

struct SweepOptions {
    std::string scene = "temple";
    uint32_t width = 256, height = 160;
    int frames = 48;                      // frames per seed run, from a reset
    int first_checkpoint = 23;            // checkpoints: first, first + every, ... < frames (each with its previous frame)
    int checkpoint_every = 8;
    int seeds = 8;                        // ensemble members (>= 2; the issue asks >= 8)
    int reference_samples = 256;          // env rays per pixel and soft light points of the target (pcf's is exact)
    std::vector<int> rrc_taps = {1, 2, 4, 8};
    std::vector<int> brute_taps = {1, 2, 4, 8, 9, 16, 32, 64};
    std::vector<float> lambdas = {0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 0.95f};
    std::vector<uint32_t> soft_caps = {8, 16, 32, 64, 128, 255};  // soft's running-mean rows
    bool catmull_rom = true;              // also the Catmull-Rom history filter (else bilinear only)
    bool rotated = true;                  // pcf: the paper's rotated pattern as extra rows
    bool finishing = true;                // 0.4's finishing steps as age-aware rows (sweep_configs.cpp)
    bool antilag = true;                  // 0.5's lag detector as age-aware rows, pcf and env (sweep_configs.cpp)
    bool blur_bound = true;               // 0.6's blur bound as age-aware rows, pcf, env and soft (sweep_configs.cpp)
    bool view_lobe = true;                // 0.7's view lobe as age-aware rows, env only (sweep_configs.cpp)
    bool pcf_base_in_signal = false;      // the pcf signal pass writes the residual's base, as rrc-sample's renderer does
    uint32_t signals = 0;                 // rrc_sample Signal bits; 0 = every signal the scene uses
    std::string motion = "all";           // all (the sample's), camera-still (the torus moves), still (nothing moves)
    float light_speed = 0.0f;             // the moving light: degrees a frame the sun and environment turn (Scene::light_speed)
    std::string study;                    // "" the sweep; "rectify" the rectification study (rectify_study.h)
    std::vector<float> rectify_gammas = {0.5f, 1.0f, 1.5f};  // the study's rectify-on rows
    std::vector<float> antilag_gammas = {1.0f, 0.75f, 0.25f}; // the study's lag-detector rows (pcf, env; --no-antilag drops them)
    float antilag_threshold = 0.25f;                          // their T (docs/CONVENTIONS.md, "The lag detector")
    std::vector<float> lobe_pixels = {18.0f};  // the study's env view-lobe rows with the lighting's turn, in pixels of the vertical angle
    std::vector<float> preset_lobes;           // the study's env preset again with each of these view lobes, radians (none by default)
    float change_threshold = 0.05f;       // the study: a pcf/soft target changed when it moved by more (env: 3 sigma of its noise)
    bool bias_maps = false;               // --bias-maps: per-pixel bias maps and bias² by region (bias_regions.h)
    int change_window = 16;               // --bias-maps: a pixel's target "changed" when it did in any of the last W frames
    std::string clock = "auto";           // auto (wall on a CPU device, timestamps otherwise), wall or timestamps
    std::string out = "out/sweep";
    bool plots = true;                    // run fronts.py at the end
    bool validation = false;
    std::string device;
    bool quiet = false;
    bool help = false;
    bool check_options = false;  // --check-options: validate, print "options ok", exit

    std::vector<int> checkpoints() const;
};

/** The host programs' one parser's error (options_parser.h). */
using rrc_host::OptionError;

SweepOptions parse_sweep_options(int argc, const char* const* argv);
std::string sweep_usage();

}  // namespace rrc_sweep
