#include "sweep_options.h"

#include "options.h"
#include "scene.h"

#include <cerrno>
#include <cstdlib>
#include <sstream>

namespace rrc_sweep {
namespace {

using rrc_sample::to_float;
using rrc_sample::to_int;

std::vector<std::string> split(const std::string& opt, const std::string& v) {
    std::vector<std::string> items;
    std::stringstream ss(v);
    std::string item;
    while (std::getline(ss, item, ',')) items.push_back(item);
    if (items.empty()) throw OptionError(opt + ": expected a comma-separated list, got \"" + v + "\"");
    return items;
}

}  // namespace

std::vector<int> SweepOptions::checkpoints() const {
    std::vector<int> c;
    for (int t = first_checkpoint; t < frames; t += checkpoint_every) c.push_back(t);
    return c;
}

std::string sweep_usage() {
    return "usage: rrc-sweep [options]\n"
           "Error against run time (docs/PERFORMANCE.md, \"Error against run time\"): rrc-sample's scene and\n"
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
           "                           env rectified, soft with the spatial fill, fill_age 8, no fallback)\n"
           "  --signals LIST           pcf,env,soft (default: every signal the scene uses)\n"
           "  --motion M               all (default: the sample's moving camera and torus), camera-still (the torus\n"
           "                           still moves: its shadow lags, no camera resampling) or still (nothing moves)\n"
           "  --light-speed DEG        the moving light: the sun and the environment map turn DEG degrees a frame about\n"
           "                           the vertical axis (default 0: fixed; the area lamp of soft shadows never moves)\n"
           "  --study rectify          the rectification study instead of the sweep (README.md, \"Rectification study\"):\n"
           "                           lag error with the light moving, static variance with it fixed, rectify off/on;\n"
           "                           its defaults unless given: --size 192x128 --checkpoints 23,4 --lambdas 0.6,0.8,0.9\n"
           "                           --taps 4 --light-speed 1 --motion still --out out/rectify\n"
           "  --rectify-gammas LIST    the study's rectify-on rows, one per gamma (default 0.5,1,1.5)\n"
           "  --change-threshold T     the study's changed pixels (pcf, soft): the target moved by more than T since the\n"
           "                           frame before (default 0.05); env's: by more than 3 sigma of its target's noise\n"
           "  --clock C                auto (default: the wall clock of each pass's own submission on a CPU device\n"
           "                           such as lavapipe, whose timestamps are wrong after graphics work; GPU\n"
           "                           timestamps otherwise), wall or timestamps\n"
           "  --out DIR                output directory (default out/sweep)\n"
           "  --no-plots               do not run fronts.py\n"
           "  --validation             Khronos validation layer with synchronization validation (exit 1 on a message)\n"
           "  --device TEXT            the first Vulkan device whose name contains TEXT (or RRC_DEVICE)\n"
           "  --quiet                  no progress lines\n"
           "  --help                   this text\n";
}

SweepOptions parse_sweep_options(int argc, const char* const* argv) {
    SweepOptions o;
    // What was given, so that --study rectify fills in only the rest with its own defaults.
    bool given_size = false, given_checkpoints = false, given_lambdas = false, given_taps = false, given_speed = false,
         given_motion = false, given_out = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw OptionError(a + ": missing value");
            return argv[++i];
        };
        if (a == "--help" || a == "-h")
            o.help = true;
        else if (a == "--scene")
            o.scene = value();
        else if (a == "--size") {
            const std::string v = value();
            const size_t x = v.find('x');
            if (x == std::string::npos) throw OptionError("--size: expected WxH, got \"" + v + "\"");
            o.width = (uint32_t)to_int(a, v.substr(0, x), 8, 8192);
            o.height = (uint32_t)to_int(a, v.substr(x + 1), 8, 8192);
            given_size = true;
        } else if (a == "--frames")
            o.frames = (int)to_int(a, value(), 2, 100000);
        else if (a == "--checkpoints") {
            const std::vector<std::string> v = split(a, value());
            if (v.size() != 2) throw OptionError("--checkpoints: expected FIRST,EVERY");
            o.first_checkpoint = (int)to_int(a, v[0], 1, 100000);
            o.checkpoint_every = (int)to_int(a, v[1], 1, 100000);
            given_checkpoints = true;
        } else if (a == "--seeds")
            o.seeds = (int)to_int(a, value(), 2, 1000);
        else if (a == "--reference-samples")
            o.reference_samples = (int)to_int(a, value(), 1, 65536);
        else if (a == "--taps" || a == "--brute-taps") {
            std::vector<int>& list = a == "--taps" ? o.rrc_taps : o.brute_taps;
            list.clear();
            for (const std::string& s : split(a, value())) list.push_back((int)to_int(a, s, 1, 64));
            given_taps |= a == "--taps";
        } else if (a == "--lambdas") {
            o.lambdas.clear();
            for (const std::string& s : split(a, value())) o.lambdas.push_back(to_float(a, s, 0.0f, 0.9999f));
            given_lambdas = true;
        } else if (a == "--change-threshold")
            o.change_threshold = to_float(a, value(), 0.0f, 10.0f);
        else if (a == "--rectify-gammas") {
            o.rectify_gammas.clear();
            for (const std::string& s : split(a, value())) o.rectify_gammas.push_back(to_float(a, s, 0.01f, 8.0f));
        } else if (a == "--soft-caps") {
            o.soft_caps.clear();
            for (const std::string& s : split(a, value())) o.soft_caps.push_back((uint32_t)to_int(a, s, 1, 65535));
        } else if (a == "--bilinear-only")
            o.catmull_rom = false;
        else if (a == "--no-rotated")
            o.rotated = false;
        else if (a == "--no-finishing")
            o.finishing = false;
        else if (a == "--signals") {
            o.signals = 0;
            for (const std::string& s : split(a, value())) {
                if (s == "pcf") o.signals |= rrc_sample::kSignalPcf;
                else if (s == "env") o.signals |= rrc_sample::kSignalEnv;
                else if (s == "soft") o.signals |= rrc_sample::kSignalSoft;
                else throw OptionError("--signals: unknown signal \"" + s + "\" (pcf, env, soft)");
            }
        } else if (a == "--motion") {
            o.motion = value();
            if (o.motion != "all" && o.motion != "camera-still" && o.motion != "still")
                throw OptionError("--motion: expected all, camera-still or still, got \"" + o.motion + "\"");
            given_motion = true;
        } else if (a == "--light-speed") {
            o.light_speed = to_float(a, value(), -180.0f, 180.0f);
            given_speed = true;
        } else if (a == "--study") {
            o.study = value();
            if (o.study != "rectify") throw OptionError("--study: expected rectify, got \"" + o.study + "\"");
        } else if (a == "--clock") {
            o.clock = value();
            if (o.clock != "auto" && o.clock != "wall" && o.clock != "timestamps")
                throw OptionError("--clock: expected auto, wall or timestamps, got \"" + o.clock + "\"");
        } else if (a == "--out")
            o.out = value(), given_out = true;
        else if (a == "--no-plots")
            o.plots = false;
        else if (a == "--validation")
            o.validation = true;
        else if (a == "--device")
            o.device = value();
        else if (a == "--quiet")
            o.quiet = true;
        else
            throw OptionError("unknown option \"" + a + "\" (--help lists them)");
    }
    if (o.study == "rectify") {
        if (!given_size) o.width = 192, o.height = 128;
        if (!given_checkpoints) o.first_checkpoint = 23, o.checkpoint_every = 4;
        if (!given_lambdas) o.lambdas = {0.6f, 0.8f, 0.9f};
        if (!given_taps) o.rrc_taps = {4};
        if (!given_speed) o.light_speed = 1.0f;
        if (!given_motion) o.motion = "still";
        if (!given_out) o.out = "out/rectify";
        if (o.light_speed == 0.0f) throw OptionError("--study rectify: the light must move (--light-speed not 0)");
    }
    if (o.checkpoints().empty())
        throw OptionError("--checkpoints: no checkpoint frame below --frames " + std::to_string(o.frames));
    for (int k : o.rrc_taps)
        if (k > 64) throw OptionError("--taps: at most 64");
    return o;
}

}  // namespace rrc_sweep
