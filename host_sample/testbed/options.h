// rrc-sample's command line.
#pragma once

#include "channel_presets.h"
#include "options_parser.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rrc_sample {

struct Options {
    std::string scene = "temple";
    int frames = 60;
    uint32_t width = 256, height = 160;
    std::string out = "out/sample";
    int reference_every = 10;           // checkpoint frames: t % K == K-1, and the last frame; 0 = none
    int reference_samples = 256;        // per pixel (pcf taps, env sub-pixel rays, soft shadow maps)
    int taps = 4;                       // k: pcf taps and env sub-pixel samples per frame
    uint32_t signals = 0;               // Signal bits; 0 = every signal the scene uses
    uint32_t reprojection = 0;          // RRC_REPROJECTION_*
    float epsilon_scale = 0.0f;         // > 0: rrc's epsilon_scale (ulps of FLOAT32 depth), a FIXED test; 0 = none given
    uint32_t depth_test = 0;            // RRC_DEPTH_TEST_*; 0 = the library's default (ADAPTIVE when no epsilon is given)
    float soft_prior = 4.0f;            // PCSS fallback weight, in samples (see README.md)
    float fill_prior = -1.0f;           // --fill-prior: the PCSS fallback's weight in rrc's fill (with --soft-fill); < 0: the preset's
    uint32_t fill_radius = 0;           // --fill-radius (0: the library's default)
    int pcf_fill_radius = -1;           // --pcf-fill-radius (-1: the preset's, the library's 5x5)
    float fill_depth_tolerance = 0.0f;  // --fill-depth-tolerance (0: the library's default)
    // Without --soft-fill the three fill options are parsed but rrc gets no fill members.
    bool base = true;                        // --no-base: the library's presets without their bases (none rendered)
    ChannelPresets channels;                 // the presets, then --lambda, --blend, --history-filter (pcf and env), --soft-age-cap
    // env's view lobe (channel_presets.h): in pixels of the camera's vertical angle (run_sample
    // turns it into radians with the scene's fov and --size); --env-view-lobe A sets radians
    // instead (channels.env.view_lobe), and then this is 0.
    float env_view_lobe_px = 0.0f;  // 0: the preset's lobe in radians (docs/reference/presets.md)
    uint32_t seed = 0;                       // ensemble member: moves every random stream
    uint32_t pcf_pattern = 0;                // 0 uniform disk (unbiased for the target), 1 the paper's rotated Poisson disk
    uint32_t env_base = kSampleEnvBase;      // --env-residual's base: 1 centre, 2 unbumped, 3 smooth, 4 filtered (the preset); 0 off
    uint32_t pcf_base = kSamplePcfBaseTaps;  // --pcf-residual's base: that many bilinear shadow compares (0 off)
    float fps = 30.0f;                       // animation time step = 1/fps
    uint32_t sun_map = 512, lamp_map = 512;  // shadow-map sizes
    float pcf_radius = 3.0f;                 // PCF disk radius in sun-map texels
    bool static_camera = false;              // hold the camera still (the mover still moves)
    bool frozen_mirror_view = false;         // the mirror reflects as seen from frame 0's eye (Scene::frozen_mirror_view)
    // The finishing steps (README.md, "Finishing steps"): display-only PCF remaps (never fed back to rrc).
    bool pcf_smoothstep = false;
    float pcf_smooth_e0 = 0.0f, pcf_smooth_e1 = 1.0f;  // --pcf-smoothstep E0,E1
    float pcf_threshold = -1.0f;                       // --pcf-threshold X; < 0: off
    std::vector<int> reference_frames;                 // --reference-frames: extra checkpoint frames
    bool dump_soft = false;                            // --dump-soft: raw float images of soft's displays on checkpoints
    uint32_t young_ages = 8;                           // --young-ages: the young-pixel table's ages 1..N
    float light_speed = 0.0f;                          // the moving light, degrees a frame (Scene::light_speed); 0 = fixed
    bool object_id = true;                             // give rrc the G-buffer's object ids (rrc_context_desc.use_object_id)
    bool validation = false;
    bool quiet = false;
    bool write_images = true;  // PNG/EXR per frame; the summary is always written
    std::string device;        // substring of the Vulkan device name
    bool help = false;
    bool check_options = false;  // --check-options: validate, print "options ok", exit
};

/** The host programs' one parser's error (options_parser.h). */
using rrc_host::OptionError;

/** --scene NAME at the cursor, one of Scene::names() (shared with rrc-sweep). */
std::string scene_name(rrc_host::ArgCursor& c);
/** --validation, --device TEXT or --quiet at the cursor (shared with rrc-sweep); false if none of them. */
bool device_option(rrc_host::ArgCursor& c, bool& validation, std::string& device, bool& quiet);
/** The help lines of device_option's options, --check-options and --help (rrc-sample's and rrc-sweep's). */
std::string device_options_help(const char* program);
/** --signals LIST (pcf,env,soft) at the cursor, as Signal bits (shared with rrc-sweep). */
uint32_t signal_bits(rrc_host::ArgCursor& c);

/** Parses argv; throws OptionError with a readable message. */
Options parse_options(int argc, const char* const* argv);
std::string usage();
/** "pcf,env,soft" for Signal bits. */
std::string signal_list(uint32_t signals);
const char* reprojection_name(uint32_t reprojection);
/** --env-residual's name of an env base (Options::env_base; shaders/signal_modes.h), "?" if none. */
const char* env_base_name(uint32_t base);
/** "default", "adaptive" or "fixed". */
const char* depth_test_name(uint32_t depth_test);
/** The test rrc applies for these options, in words (summary, progress). */
std::string depth_test_description(const Options& options);

}  // namespace rrc_sample
