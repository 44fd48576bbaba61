#include "sweep_options.h"

#include "options.h"
#include "scene.h"

#include <rrc/rrc.h>


namespace rrc_sweep {
namespace {

using Name = rrc_host::EnumName<const char*>;
constexpr Name kMotionNames[] = {{"all", "all"}, {"camera-still", "camera-still"}, {"still", "still"}};
constexpr Name kStudyNames[] = {{"rectify", "rectify"}, {"clean", "clean"}};
constexpr Name kClockNames[] = {{"auto", "auto"}, {"wall", "wall"}, {"timestamps", "timestamps"}};

std::vector<int> ints(const std::vector<long>& v) { return std::vector<int>(v.begin(), v.end()); }

}  // namespace

std::vector<int> SweepOptions::checkpoints() const {
    std::vector<int> c;
    for (int t = first_checkpoint; t < frames; t += checkpoint_every) c.push_back(t);
    return c;
}

std::string sweep_usage() {
    return "usage: rrc-sweep [options]\n"
           "Error against run time (docs/measurements/PERFORMANCE.md, \"Error against run time\"): rrc-sample's scene and\n"
           "signals, brute force at k samples a frame against rrc at k samples a frame for every lambda, blend\n"
           "and history filter, over an ensemble of seeds, scored against one target per application that\n"
           "does not depend on k or lambda.  Writes sweep_<app>.csv, hit_ratio.csv, sweep.md and (fronts.py)\n"
           "the Pareto fronts' plots and verdicts.\n"
           "\n"
           "  --scene NAME             temple (default) or courtyard\n"
           "  --size WxH               resolution (default 256x160)\n"
           "  --frames N               frames per run from a reset (default 48)\n"
           "  --checkpoints A,E        scored frames A, A+E, ... < N, each with its previous frame (default 23,8)\n"
           "  --seeds S                ensemble members, >= 2 (default 8)\n"
           "  --reference-samples N    env rays and soft light points of the target (default 256; pcf's is exact)\n"
           "  --taps LIST              rrc's k values (default 1,2,4,8)\n"
           "  --brute-taps LIST        brute force's k values (default 1,2,4,8,9,16,32,64)\n"
           "  --lambdas LIST           lambda values of the fixed and age-aware rows (default 0.5,0.6,0.7,0.8,0.9,0.95)\n"
           "  --soft-caps LIST         age caps of soft's running-mean rows (default 8,16,32,64,128,255)\n"
           "  --bilinear-only          no Catmull-Rom rows\n"
           "  --no-rotated             no rows for the paper's rotated PCF pattern\n"
           "  --no-finishing           no rows for the finishing steps (age-aware: pcf rectified and Gaussian history,\n"
           "                           env rectified, soft with the spatial fill, fill_age 8, no fallback) and no row for\n"
           "                           rrc-sample's soft preset (its fill with the PCSS fallback, fill_prior 4)\n"
           "  --no-antilag             no rows for the lag detector (age-aware, gamma_a 1, threshold 0.25: pcf rectified,\n"
           "                           env; never soft); in the study also no rrc-sample preset rows\n"
           "  --no-blur-bound          no rows for the blur bound (age-aware, bilinear, B 0.5 px^2: pcf rectified, env,\n"
           "                           soft with the fill rows' settings)\n"
           "  --no-view-lobe           no rows for the view lobe (env only: age-aware, bilinear, alpha 0.0245 rad; its\n"
           "                           age cap is 1 on the mirror sphere)\n"
           "  --pcf-base-in-signal     the pcf signal pass also writes the residual's base, as rrc-sample's renderer\n"
           "                           does (its G-buffer reads and light transform paid once): a residual row's signal\n"
           "                           time is then that pass, base included, and its rrc time rrc's dispatch alone;\n"
           "                           other pcf rows keep the brute-force pass at their k where one is timed, else\n"
           "                           the same pass (default: the base is a pass of its own, timed with rrc)\n"
           "  --signals LIST           pcf,env,soft (default: every signal the scene uses)\n"
           "  --motion M               all (default: the sample's moving camera and torus), camera-still (the torus\n"
           "                           still moves: its shadow lags, no camera resampling) or still (nothing moves)\n"
           "  --light-speed DEG        the moving light: the sun and the environment map turn DEG degrees a frame about\n"
           "                           the vertical axis (default 0: fixed; the area lamp of soft shadows never moves)\n"
           "  --study rectify          the rectification study instead of the sweep (README.md, \"Rectification study\"):\n"
           "                           lag error with the light moving, static variance with it fixed, rectify off/on;\n"
           "                           its defaults unless given: --size 192x128 --checkpoints 23,4 --lambdas 0.6,0.8,0.9\n"
           "                           --taps 4 --light-speed 1 --motion still --out out/rectify\n"
           "  --study clean            what rrc adds to a clean input (README.md, \"Clean input\"): each application's target\n"
           "                           (--reference-samples) as its per-frame signal, accumulated with\n"
           "                           rrc-sample's preset with and without its base, and the output against that frame's\n"
           "                           input by region (background, edge, filled, miss, young, history): clean.md and\n"
           "                           clean.csv; its defaults unless given: --frames 24 --checkpoints 8,1 --out out/clean\n"
           "  --rectify-gammas LIST    the study's rectify-on rows, one per gamma (default 0.5,1,1.5)\n"
           "  --antilag-gammas LIST    the study's lag-detector rows (pcf, env), one per gamma_a (default 1,0.75,0.25;\n"
           "                           --no-antilag drops them)\n"
           "  --antilag-threshold T    their threshold T (default 0.25)\n"
           "  --lobe-pixels LIST       the study's env rows with the view lobe fed the lighting's turn, one per lobe in\n"
           "                           pixels of the vertical angle (default 18, rrc-sample's; --no-view-lobe drops them)\n"
           "  --preset-lobes LIST      the study's env preset row again with each of these view lobes in radians, in\n"
           "                           (0, pi], in place of its own (default none; dropped with the preset rows)\n"
           "  --change-threshold T     the study's changed pixels (pcf, soft): the target moved by more than T since the\n"
           "                           frame before (default 0.05); env's: by more than 3 sigma of its target's noise\n"
           "  --bias-maps              also the signed bias maps (seed mean - target) of every row at every checkpoint\n"
           "                           and its bias² and variance split by region (object, edge, young, changed,\n"
           "                           static; README.md, \"Bias maps\"): bias_regions_<app>.csv, bias_maps/*.exr, and\n"
           "                           (bias_maps.py) bias_regions_<app>.md and bias_<app>.png\n"
           "  --change-window W        --bias-maps: a pixel's target changed when its surface point's target differed\n"
           "                           from the current one in any of the last W frames (default 16)\n"
           "  --clock C                auto (default: the wall clock of each pass's own submission on a CPU device\n"
           "                           such as lavapipe, whose timestamps are wrong after graphics work; GPU\n"
           "                           timestamps otherwise), wall or timestamps\n"
           "  --out DIR                output directory (default out/sweep)\n"
           "  --no-plots               do not run fronts.py\n"
           + rrc_sample::device_options_help("rrc-sweep");
}

SweepOptions parse_sweep_options(int argc, const char* const* argv) {
    SweepOptions o;
    rrc_host::ArgCursor c(argc, argv);
    while (c.next()) {
        if (c.option("--scene"))
            o.scene = rrc_sample::scene_name(c);
        else if (c.option("--size"))
            c.size(o.width, o.height, 8, 8192);
        else if (c.option("--frames"))
            o.frames = (int)c.integer(2, 100000);
        else if (c.option("--checkpoints")) {
            const std::vector<long> v = c.integers(1, 100000);
            if (v.size() != 2) c.fail("expected FIRST,EVERY");
            o.first_checkpoint = (int)v[0];
            o.checkpoint_every = (int)v[1];
        } else if (c.option("--seeds"))
            o.seeds = (int)c.integer(2, 1000);
        else if (c.option("--reference-samples"))
            o.reference_samples = (int)c.integer(1, 65536);
        else if (c.option("--taps"))
            o.rrc_taps = ints(c.integers(1, 64));
        else if (c.option("--brute-taps"))
            o.brute_taps = ints(c.integers(1, 64));
        else if (c.option("--lambdas"))
            o.lambdas = c.numbers(0.0f, 0.9999f);
        else if (c.option("--change-threshold"))
            o.change_threshold = c.number(0.0f, 10.0f);
        else if (c.option("--rectify-gammas"))
            o.rectify_gammas = c.numbers(0.01f, 8.0f);
        else if (c.option("--lobe-pixels"))
            o.lobe_pixels = c.numbers(0.01f, 1e4f);
        else if (c.option("--preset-lobes"))
            o.preset_lobes = c.numbers(1e-4f, RRC_MAX_VIEW_LOBE);
        else if (c.option("--antilag-gammas"))
            o.antilag_gammas = c.numbers(0.01f, RRC_MAX_ANTILAG_GAMMA);
        else if (c.option("--antilag-threshold"))
            o.antilag_threshold = c.number(0.01f, RRC_MAX_ANTILAG_THRESHOLD);
        else if (c.option("--soft-caps")) {
            o.soft_caps.clear();
            for (long cap : c.integers(1, 65535)) o.soft_caps.push_back((uint32_t)cap);
        } else if (c.flag("--bilinear-only"))
            o.catmull_rom = false;
        else if (c.flag("--no-rotated"))
            o.rotated = false;
        else if (c.flag("--no-finishing"))
            o.finishing = false;
        else if (c.flag("--no-antilag"))
            o.antilag = false;
        else if (c.flag("--no-blur-bound"))
            o.blur_bound = false;
        else if (c.flag("--no-view-lobe"))
            o.view_lobe = false;
        else if (c.flag("--pcf-base-in-signal"))
            o.pcf_base_in_signal = true;
        else if (c.option("--signals"))
            o.signals = rrc_sample::signal_bits(c);
        else if (c.option("--motion"))
            o.motion = c.choice(kMotionNames);
        else if (c.option("--light-speed"))
            o.light_speed = c.number(-180.0f, 180.0f);
        else if (c.option("--study"))
            o.study = c.choice(kStudyNames);
        else if (c.option("--clock"))
            o.clock = c.choice(kClockNames);
        else if (c.option("--out"))
            o.out = c.value();
        else if (c.option("--change-window"))
            o.change_window = (int)c.integer(1, 1000);
        else if (c.flag("--bias-maps"))
            o.bias_maps = true;
        else if (c.flag("--no-plots"))
            o.plots = false;
        else if (!rrc_sample::device_option(c, o.validation, o.device, o.quiet))
            c.unknown();
    }
    o.check_options = c.check_only();
    o.help = c.help();
    if (o.study == "rectify") {
        // What was given wins; the study fills in only the rest with its own defaults.
        if (!c.given("--size")) o.width = 192, o.height = 128;
        if (!c.given("--checkpoints")) o.first_checkpoint = 23, o.checkpoint_every = 4;
        if (!c.given("--lambdas")) o.lambdas = {0.6f, 0.8f, 0.9f};
        if (!c.given("--taps")) o.rrc_taps = {4};
        if (!c.given("--light-speed")) o.light_speed = 1.0f;
        if (!c.given("--motion")) o.motion = "still";
        if (!c.given("--out")) o.out = "out/rectify";
        if (o.light_speed == 0.0f) throw OptionError("--study rectify: the light must move (--light-speed not 0)");
    }
    if (o.study == "clean") {
        // Noise-free input: one run says all (the seeds change nothing); frames from 8 on, as the
        // error study's, every frame scored.
        if (!c.given("--frames")) o.frames = 24;
        if (!c.given("--checkpoints")) o.first_checkpoint = 8, o.checkpoint_every = 1;
        if (!c.given("--out")) o.out = "out/clean";
        if (o.bias_maps) throw OptionError("--bias-maps: the sweep's, not --study clean's");
    }
    if (o.pcf_base_in_signal && !o.study.empty())
        throw OptionError("--pcf-base-in-signal: the sweep's, not --study " + o.study + "'s");
    if (o.bias_maps && o.first_checkpoint < o.change_window)
        throw OptionError("--bias-maps: the first checkpoint must be at least --change-window frames from the reset");
    if (o.study == "rectify" && o.bias_maps) throw OptionError("--bias-maps: the sweep's, not --study rectify's");
    if (o.checkpoints().empty())
        throw OptionError("--checkpoints: no checkpoint frame below --frames " + std::to_string(o.frames));
    return o;
}

}  // namespace rrc_sweep
