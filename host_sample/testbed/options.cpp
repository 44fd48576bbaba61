#include "options.h"

#include "enum_names.h"
#include "scene.h"

#include <rrc/rrc.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace rrc_sample {
namespace {

uint32_t parse_signals(const std::string& v) {
    uint32_t bits = 0;
    std::stringstream ss(v);
    std::string item;
    while (std::getline(ss, item, ',')) {
        if (item == "pcf")
            bits |= kSignalPcf;
        else if (item == "env")
            bits |= kSignalEnv;
        else if (item == "soft")
            bits |= kSignalSoft;
        else
            throw OptionError("--signals: unknown signal \"" + item + "\" (pcf, env, soft)");
    }
    if (!bits) throw OptionError("--signals: name at least one of pcf, env, soft");
    return bits;
}

}  // namespace

long to_int(const std::string& opt, const std::string& v, long lo, long hi) {
    char* end = nullptr;
    errno = 0;
    long x = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end || errno || x < lo || x > hi)
        throw OptionError(opt + ": expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got \"" + v + "\"");
    return x;
}

float to_float(const std::string& opt, const std::string& v, float lo, float hi) {
    char* end = nullptr;
    errno = 0;
    float x = std::strtof(v.c_str(), &end);
    if (v.empty() || *end || errno || !(x >= lo && x <= hi))
        throw OptionError(opt + ": expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got \"" + v + "\"");
    return x;
}

std::string signal_list(uint32_t s) {
    std::string out;
    if (s & kSignalPcf) out += "pcf,";
    if (s & kSignalEnv) out += "env,";
    if (s & kSignalSoft) out += "soft,";
    if (!out.empty()) out.pop_back();
    return out;
}

const char* reprojection_name(uint32_t r) { return rrc_host::enum_name(rrc_host::kReprojectionNames, r); }

namespace {
// host_sample/common/enum_names.h has no depth-test table yet; the sample keeps its own.
constexpr rrc_host::EnumName<rrc_depth_test> kDepthTestNames[] = {{"adaptive", RRC_DEPTH_TEST_ADAPTIVE}, {"fixed", RRC_DEPTH_TEST_FIXED}};
}  // namespace

const char* depth_test_name(uint32_t t) {
    return t == RRC_DEPTH_TEST_DEFAULT ? "default" : rrc_host::enum_name(kDepthTestNames, (rrc_depth_test)t);
}

std::string depth_test_description(const Options& o) {
    char scale[32];
    std::snprintf(scale, sizeof scale, "%g", o.epsilon_scale > 0.0f ? o.epsilon_scale : RRC_DEFAULT_EPSILON_SCALE_FLOAT32);
    if (o.depth_test == RRC_DEPTH_TEST_ADAPTIVE) return "adaptive (--depth-test adaptive)";
    if (o.epsilon_scale > 0.0f) return std::string("fixed, epsilon ") + scale + " ulp (--epsilon-scale)";
    if (o.depth_test == RRC_DEPTH_TEST_FIXED)
        return std::string("fixed, epsilon ") + scale + " ulp (--depth-test fixed, the library's scale)";
    return "the library's default (no epsilon given: adaptive for an API 0.2 caller)";
}

std::string usage() {
    return "usage: rrc-sample [options]\n"
           "A headless Vulkan renderer driving rrc through its interop path: an animated temple scene,\n"
           "three noisy per-frame signals accumulated by rrc, a brute-force reference on checkpoint frames.\n"
           "\n"
           "  --scene NAME             temple (default: pcf, env, soft) or courtyard (no mirror sphere)\n"
           "  --frames N               frames to render (default 60)\n"
           "  --size WxH               resolution (default 256x160)\n"
           "  --out DIR                output directory (default out/sample)\n"
           "  --reference-every K      brute-force reference on frames K-1, 2K-1, ... and the last (default 10; 0 = none)\n"
           "  --reference-samples N    samples per pixel of the reference (default 256)\n"
           "  --taps k                 PCF taps and env sub-pixel samples per frame (default 4)\n"
           "  --signals LIST           pcf,env,soft (default: every signal the scene uses)\n"
           "  --reproject SRC          prev_clip (default), motion, motion_depth or camera\n"
           "  --depth-test TEST        adaptive or fixed (default: none given, the library's default test, which is\n"
           "                           adaptive for this API 0.2 caller when no --epsilon-scale is given; see README.md)\n"
           "  --epsilon-scale S        a fixed depth test with epsilon = S ulps of the fp32 depth (default: none given;\n"
           "                           0 = the library default, 4 ulp under --depth-test fixed; not with --depth-test adaptive)\n"
           "  --soft-prior N           weight of the PCSS fallback on young soft-shadow pixels, in samples (default 4)\n"
           "  --soft-age-cap N         the soft channel's age cap (default 64)\n"
           "  --soft-fill T            rrc's spatial fill on the soft channel for pixels younger than T frames (fill_age;\n"
           "                           default 8, the preset; 0 = off); the display then shows rrc's output, not the\n"
           "                           --soft-prior blend\n"
           "  --fill-radius R          the fill's window half width (default 0: the library's, 2)\n"
           "  --fill-depth-tolerance D the fill's relative depth tolerance (default 0: the library's, 0.005)\n"
           "  --fill-prior P           the PCSS estimate's weight in the fill, in samples, passed to rrc as the soft channel's\n"
           "                           fallback image (default 4; 0 = no fallback)\n"
           "  --blur-sigma S           the pcf channel's Gaussian blur (with --history-filter gaussian; default 0: the library's 0.5)\n"
           "  --pcf-smoothstep E0,E1   display only: show smoothstep(E0, E1, pcf) (never fed back to rrc)\n"
           "  --pcf-threshold X        display only: show pcf >= X as 1, else 0 (after the smoothstep, if any)\n"
           "  --pcf-confidence         the pcf signal pass writes the shadow-map test confidence per pixel (Scherzer 2007);\n"
           "                           the pcf channel gets confidence = 1 and that image\n"
           "  --reference-frames LIST  also take the reference on these frames (comma separated)\n"
           "  --dump-soft              on checkpoints write finish/soft_<what>_NNNN.f32 (raw float images of soft's displays)\n"
           "  --young-ages N           the young-pixel table (young.csv): ages 1..N (default 8)\n"
           "  --model-fill-age T       T of the fill's CPU model, scored in young.csv without --soft-fill (default 8)\n"
           "  --lambda L               pcf and env channels' lambda, in [0, 1) (default: pcf 0.7, env 0.8)\n"
           "  --rectify G              pcf and env channels' history rectification with gamma G (0 = off; default: pcf 1,\n"
           "                           env off: the presets, channel_presets.h)\n"
           "  --blend B                pcf and env channels' blend: fixed, age_aware (default) or running_mean\n"
           "  --history-filter F       every channel's history resampling: bilinear (default), catmull_rom or nearest;\n"
           "                           gaussian: the pcf channel's only (the others stay bilinear)\n"
           "  --pcf-pattern P          disk (default: k taps uniform over the filter disk, unbiased for the exact disk\n"
           "                           mean the reference is) or rotated (the paper's Poisson disk, rotated per pixel)\n"
           "  --seed N                 ensemble member: moves every random stream of the signals (default 0)\n"
           "  --fps F                  animation frames per second of scene time (default 30)\n"
           "  --shadow-map-size S      sun and lamp shadow maps, S x S texels (default 512)\n"
           "  --pcf-radius R           PCF disk radius in sun shadow-map texels (default 3)\n"
           "  --static-camera          keep the camera still (the torus still moves)\n"
           "  --light-speed DEG        the moving light: the sun and the environment map turn DEG degrees a frame\n"
           "                           about the vertical axis (default 0: fixed; the area lamp never moves)\n"
           "  --no-object-id           do not give rrc the G-buffer's per-pixel object ids (default: given, so a hit\n"
           "                           also needs every previous-depth tap to show the pixel's object; see README.md)\n"
           "  --no-images              write only summary.md, summary.csv and errors.csv\n"
           "  --validation             Khronos validation layer with synchronization validation\n"
           "  --device TEXT            use the first Vulkan device whose name contains TEXT (or RRC_DEVICE)\n"
           "  --quiet                  no per-frame progress\n"
           "  --help                   this text\n";
}

Options parse_options(int argc, const char* const* argv) {
    Options o;
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
        else if (a == "--frames")
            o.frames = (int)to_int(a, value(), 1, 100000);
        else if (a == "--size") {
            const std::string v = value();
            const size_t x = v.find('x');
            if (x == std::string::npos) throw OptionError("--size: expected WxH, got \"" + v + "\"");
            o.width = (uint32_t)to_int(a, v.substr(0, x), 8, 8192);
            o.height = (uint32_t)to_int(a, v.substr(x + 1), 8, 8192);
        } else if (a == "--out")
            o.out = value();
        else if (a == "--reference-every")
            o.reference_every = (int)to_int(a, value(), 0, 100000);
        else if (a == "--reference-samples")
            o.reference_samples = (int)to_int(a, value(), 1, 65536);
        else if (a == "--taps")
            o.taps = (int)to_int(a, value(), 1, 64);
        else if (a == "--signals")
            o.signals = parse_signals(value());
        else if (a == "--reproject") {
            const std::string v = value();
            if (!rrc_host::enum_value(rrc_host::kReprojectionNames, v, o.reprojection))
                throw OptionError("--reproject: expected " + rrc_host::enum_choices(rrc_host::kReprojectionNames) + ", got \"" + v + "\"");
        } else if (a == "--depth-test") {
            const std::string v = value();
            rrc_depth_test t{};
            if (!rrc_host::enum_value(kDepthTestNames, v, t))
                throw OptionError("--depth-test: expected " + rrc_host::enum_choices(kDepthTestNames) + ", got \"" + v + "\"");
            o.depth_test = (uint32_t)t;
        } else if (a == "--epsilon-scale")
            o.epsilon_scale = to_float(a, value(), 0.0f, 1e9f);
        else if (a == "--soft-prior")
            o.soft_prior = to_float(a, value(), 0.0f, 1e6f);
        else if (a == "--soft-age-cap")
            o.channels.soft.age_cap = (uint32_t)to_int(a, value(), 1, RRC_MAX_AGE_CAP);
        else if (a == "--lambda")
            o.channels.pcf.lambda = o.channels.env.lambda = to_float(a, value(), 0.0f, 0.9999f);
        else if (a == "--rectify") {
            const float g = to_float(a, value(), 0.0f, RRC_MAX_RECTIFY_GAMMA);
            for (ChannelSettings* c : {&o.channels.pcf, &o.channels.env}) {
                c->rectify = g > 0.0f ? 1u : 0u;
                c->rectify_gamma = g == RRC_DEFAULT_RECTIFY_GAMMA ? 0.0f : g;
            }
        }
        else if (a == "--blend") {
            const std::string v = value();
            if (!rrc_host::enum_value(rrc_host::kBlendNames, v, o.channels.pcf.blend))
                throw OptionError("--blend: expected " + rrc_host::enum_choices(rrc_host::kBlendNames) + ", got \"" + v + "\"");
            o.channels.env.blend = o.channels.pcf.blend;
        } else if (a == "--history-filter" && i + 1 < argc && std::string(argv[i + 1]) == "gaussian") {
            // GAUSSIAN is the pcf channel's only (the amortized-PCF chapter's blur).
            ++i;
            o.channels.pcf.filter = RRC_HISTORY_FILTER_GAUSSIAN;
        } else if (a == "--history-filter") {
            const std::string v = value();
            if (!rrc_host::enum_value(rrc_host::kHistoryFilterNames, v, o.channels.pcf.filter))
                throw OptionError("--history-filter: expected " + rrc_host::enum_choices(rrc_host::kHistoryFilterNames) + ", got \"" + v +
                                  "\"");
            o.channels.env.filter = o.channels.soft.filter = o.channels.pcf.filter;
        } else if (a == "--pcf-pattern") {
            const std::string v = value();
            if (v != "disk" && v != "rotated") throw OptionError("--pcf-pattern: expected disk or rotated, got \"" + v + "\"");
            o.pcf_pattern = v == "rotated" ? 1u : 0u;
        } else if (a == "--seed")
            o.seed = (uint32_t)to_int(a, value(), 0, 65535);
        else if (a == "--fps")
            o.fps = to_float(a, value(), 0.1f, 10000.0f);
        else if (a == "--shadow-map-size")
            o.sun_map = o.lamp_map = (uint32_t)to_int(a, value(), 16, 8192);
        else if (a == "--pcf-radius")
            o.pcf_radius = to_float(a, value(), 0.0f, 64.0f);
        else if (a == "--soft-fill")
            o.channels.soft.fill_age = (uint32_t)to_int(a, value(), 0, RRC_MAX_AGE_CAP + 1);
        else if (a == "--fill-radius")
            o.fill_radius = (uint32_t)to_int(a, value(), 0, RRC_MAX_FILL_RADIUS);
        else if (a == "--fill-depth-tolerance")
            o.fill_depth_tolerance = to_float(a, value(), 0.0f, 1e6f);
        else if (a == "--fill-prior")
            o.fill_prior = to_float(a, value(), 0.0f, 1e6f);
        else if (a == "--blur-sigma")
            o.channels.pcf.blur_sigma = to_float(a, value(), 0.0f, RRC_MAX_BLUR_SIGMA);
        else if (a == "--pcf-smoothstep") {
            const std::string v = value();
            const size_t c = v.find(',');
            if (c == std::string::npos) throw OptionError("--pcf-smoothstep: expected E0,E1, got \"" + v + "\"");
            o.pcf_smooth_e0 = to_float(a, v.substr(0, c), -1e6f, 1e6f);
            o.pcf_smooth_e1 = to_float(a, v.substr(c + 1), -1e6f, 1e6f);
            if (!(o.pcf_smooth_e1 > o.pcf_smooth_e0)) throw OptionError("--pcf-smoothstep: needs E0 < E1");
            o.pcf_smoothstep = true;
        } else if (a == "--pcf-threshold")
            o.pcf_threshold = to_float(a, value(), 0.0f, 1.0f);
        else if (a == "--pcf-confidence")
            o.channels.pcf.confidence = 1;
        else if (a == "--reference-frames") {
            std::stringstream ss(value());
            std::string item;
            while (std::getline(ss, item, ',')) o.reference_frames.push_back((int)to_int(a, item, 0, 100000));
        } else if (a == "--dump-soft")
            o.dump_soft = true;
        else if (a == "--model-fill-age")
            o.model_fill_age = (uint32_t)to_int(a, value(), 1, RRC_MAX_AGE_CAP + 1);
        else if (a == "--young-ages")
            o.young_ages = (uint32_t)to_int(a, value(), 1, 255);
        else if (a == "--static-camera")
            o.static_camera = true;
        else if (a == "--light-speed")
            o.light_speed = to_float(a, value(), -180.0f, 180.0f);
        else if (a == "--no-object-id")
            o.object_id = false;
        else if (a == "--no-images")
            o.write_images = false;
        else if (a == "--validation")
            o.validation = true;
        else if (a == "--device")
            o.device = value();
        else if (a == "--quiet")
            o.quiet = true;
        else
            throw OptionError("unknown option \"" + a + "\" (--help lists them)");
    }
    if (o.channels.pcf.blur_sigma > 0.0f && o.channels.pcf.filter != RRC_HISTORY_FILTER_GAUSSIAN)
        throw OptionError("--blur-sigma needs --history-filter gaussian");
    // The fill's fallback is the PCSS estimate, worth --fill-prior samples; without a fill rrc takes none.
    // The fill's members go to rrc only with a fill (the library refuses them without one).
    const bool fill = o.channels.soft.fill_age != 0;
    o.channels.soft.fill_prior = fill ? o.fill_prior : 0.0f;
    o.channels.soft.fill_radius = fill ? o.fill_radius : 0u;
    o.channels.soft.fill_depth_tolerance = fill ? o.fill_depth_tolerance : 0.0f;
    // rrc refuses ADAPTIVE with an epsilon (rrc.h, rrc_context_desc.depth_test): say so here, by option name.
    if (o.depth_test == RRC_DEPTH_TEST_ADAPTIVE && o.epsilon_scale > 0.0f)
        throw OptionError("--depth-test adaptive takes no --epsilon-scale (an epsilon makes the test fixed)");
    return o;
}

}  // namespace rrc_sample
