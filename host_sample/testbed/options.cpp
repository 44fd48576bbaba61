#include "options.h"

#include "enum_names.h"
#include "options_parser.h"
#include "scene.h"

#include <rrc/rrc.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <utility>
#include <cstdio>

namespace rrc_sample {
namespace {

// rrc-sweep's --signals too.
constexpr rrc_host::EnumName<uint32_t> kSignalNames[] = {{"pcf", kSignalPcf}, {"env", kSignalEnv}, {"soft", kSignalSoft}};
constexpr rrc_host::EnumName<uint32_t> kPcfPatternNames[] = {{"disk", 0u}, {"rotated", 1u}};
constexpr rrc_host::EnumName<uint32_t> kOnOffNames[] = {{"off", 0u}, {"on", 1u}};
constexpr int kMaxPcfBaseTaps = 64;  // --pcf-residual's bilinear taps
constexpr rrc_host::EnumName<uint32_t> kEnvBaseNames[] = {{"off", SAMPLE_ENV_BASE_OFF},
                                                           {"centre", SAMPLE_ENV_BASE_CENTRE},
                                                           {"unbumped", SAMPLE_ENV_BASE_UNBUMPED},
                                                           {"smooth", SAMPLE_ENV_BASE_SMOOTH},
                                                           {"filtered", SAMPLE_ENV_BASE_FILTERED}};

}  // namespace

std::string scene_name(rrc_host::ArgCursor& c) {
    const std::string name = c.value();
    const std::vector<std::string> names = Scene::names();
    if (std::find(names.begin(), names.end(), name) == names.end()) c.fail("expected temple or courtyard");
    return name;
}

std::string device_options_help(const char* program) {
    return std::string("  --validation             Khronos validation layer with synchronization validation (exit 1 on a message)\n"
                       "  --device TEXT            the first Vulkan device whose name contains TEXT (or RRC_DEVICE)\n"
                       "  --quiet                  no progress lines\n") +
           rrc_host::check_options_help(program) + "  --help                   this text\n";
}

bool device_option(rrc_host::ArgCursor& c, bool& validation, std::string& device, bool& quiet) {
    if (c.flag("--validation"))
        validation = true;
    else if (c.option("--device"))
        device = c.value();
    else if (c.flag("--quiet"))
        quiet = true;
    else
        return false;
    return true;
}

uint32_t signal_bits(rrc_host::ArgCursor& c) {
    uint32_t bits = 0;
    for (uint32_t s : c.choices(kSignalNames)) bits |= s;
    return bits;
}

namespace {
/** A per-channel option's list: signal names, or "none" for no channel (the presets' setting off). */
uint32_t signal_bits_or_none(rrc_host::ArgCursor& c) {
    uint32_t bits = 0;
    for (const std::string& name : c.names()) {
        uint32_t s = 0;
        if (name != "none" && !rrc_host::enum_value(kSignalNames, name, s)) c.fail("expected pcf, env, soft or none");
        bits |= s;
    }
    return bits;
}
}  // namespace

std::string signal_list(uint32_t s) {
    std::string out;
    if (s & kSignalPcf) out += "pcf,";
    if (s & kSignalEnv) out += "env,";
    if (s & kSignalSoft) out += "soft,";
    if (!out.empty()) out.pop_back();
    return out;
}

const char* reprojection_name(uint32_t r) { return rrc_host::enum_name(rrc_host::kReprojectionNames, r); }

const char* env_base_name(uint32_t base) { return rrc_host::enum_name(kEnvBaseNames, base); }

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
           "  --fill-radius R          the soft fill's window half width (default 0: the library's, 2)\n"
           "  --pcf-fill-radius R      the pcf fill's window half width (default: the preset's, 0 = the library's 2 with the\n"
           "                           base, 1 with --no-base)\n"
           "  --fill-depth-tolerance D the fill's relative depth tolerance (default 0: the library's, 0.005)\n"
           "  --fill-prior P           the PCSS estimate's weight in the fill, in samples, passed to rrc as the soft channel's\n"
           "                           fallback image (default: the preset's, 4 with the base, 0 with --no-base; 0 = no fallback)\n"
           "  --no-base                the library's presets without their bases (docs/reference/presets.md): rrc-sample\n"
           "                           renders no pcf, env or soft base and passes rrc no fallback image\n"
           "  --blur-sigma S           the pcf channel's Gaussian blur (with --history-filter gaussian; default 0: the library's 0.5)\n"
           "  --pcf-smoothstep E0,E1   display only: show smoothstep(E0, E1, pcf) (never fed back to rrc)\n"
           "  --pcf-threshold X        display only: show pcf >= X as 1, else 0 (after the smoothstep, if any)\n"
           "  --pcf-confidence         the pcf signal pass writes the shadow-map test confidence per pixel (Scherzer 2007);\n"
           "                           the pcf channel gets confidence = 1 and that image\n"
           "  --reference-frames LIST  also take the reference on these frames (comma separated)\n"
           "  --dump-soft              on checkpoints write finish/soft_<what>_NNNN.f32 (raw float images of soft's displays)\n"
           "  --young-ages N           the young-pixel table (young.csv): ages 1..N (default 8)\n"
           "  --lambda L               pcf and env channels' lambda, in [0, 1) (default 0.9, both presets)\n"
           "  --rectify G              pcf and env channels' history rectification with gamma G (0 = off; default: off,\n"
           "                           the presets, channel_presets.h)\n"
           "  --antilag LIST           the lag detector on exactly these channels (pcf,env,soft, or none; default: the\n"
           "                           presets', none): a history that left its 3x3 box is shortened\n"
           "                           (docs/CONVENTIONS.md, \"The lag detector\")\n"
           "  --antilag-gamma G        its box half width in sigmas (default: the preset's on a preset channel when\n"
           "                           --antilag is not given, else the library's, 2)\n"
           "  --antilag-threshold T    its relative gap that drops the history (default: as --antilag-gamma; the\n"
           "                           library's is 0.5)\n"
           "  --blur-bound LIST        the blur bound on exactly these channels (pcf,env,soft, or none; default: the\n"
           "                           presets', none): a bilinear or Gaussian history's age is capped so its stationary\n"
           "                           resampling blur stays within --blur-bound-px2 (docs/CONVENTIONS.md, \"The blur bound\")\n"
           "  --blur-bound-px2 B       that bound in px^2 per axis, in (0, 64] (default: the preset's on a preset channel\n"
           "                           when --blur-bound is not given, else 0.5)\n"
"  --gate LIST              the deviation gate on exactly these channels (pcf,env,soft, or none; default: the\n"
           "                           presets', none): a history whose mean deviation from the samples exceeds kappa\n"
           "                           standard errors is shortened (docs/CONVENTIONS.md, \"The deviation gate\")\n"
           "  --gate-kappa K           its kappa, in (0, 16] (default: the preset's on a preset channel when --gate is\n"
           "                           not given, else 2)\n"
           "  --env-view-lobe-px P     the view-dependent history on the env channel: its age is capped at\n"
           "                           floor(A/theta), theta the turn of the view direction to the pixel's surface\n"
           "                           point since the last frame, A = P pixels of the camera's vertical angle\n"
           "                           (P * fov_y / height; 0 = off; the preset before the env residual: 18, 0.0245\n"
           "                           rad at 640 rows; docs/CONVENTIONS.md, \"The view-dependent history\")\n"
           "  --env-view-lobe A        the same lobe given in radians, in [0, pi] (default 0.08, the preset's, at every\n"
           "                           size; 0 = off; README.md, \"The env residual's view lobe\")\n"
           "  --soft-lambda L          the soft channel's lambda, in [0, 1) (default 0.95, the preset)\n"
           "  --soft-residual on|off   rrc's residual on the soft channel (rrc_channel_desc.residual): it accumulates\n"
           "                           the sample less a stable PCSS estimate, its base, shows the result plus the\n"
           "                           base, and the base is the fill's prior (default on, the preset; off: rrc\n"
           "                           accumulates the sample, PCSS is the fill's fallback; README.md, \"The soft residual\")\n"
           "  --env-residual B         rrc's residual on the env channel against a deterministic base the env pass\n"
           "                           writes: filtered (default, the preset: four reflections per pixel into the map\n"
           "                           box-filtered over each one's footprint), centre (the bumped mirror's ray through\n"
           "                           the pixel centre), unbumped (that ray reflected by the smooth sphere), smooth\n"
           "                           (reflected by the smooth sphere into the map without its hard edges) or off\n"
           "                           (rrc accumulates the sample); README.md, \"The env residual\"\n"
           "  --pcf-residual N         rrc's residual on the pcf channel against a deterministic base the sample\n"
           "                           writes: the mean of N bilinear shadow compares on a circle inside the PCF disk\n"
           "                           (default 4, the preset; 0 = off: rrc accumulates the sample; at most 64;\n"
           "                           README.md, \"The pcf residual\")\n"
           "  --pcf-fill T, --env-fill T  rrc's spatial fill (library defaults, no fallback) on the pcf / env channel for\n"
           "                           pixels younger than T frames (default: 4 on pcf, 2 on env, the presets; 0 = off)\n"
           "  --blend B                pcf and env channels' blend: fixed, age_aware (default) or running_mean\n"
           "  --history-filter F       every channel's history resampling: bilinear (default: pcf's and env's\n"
           "                           presets'), catmull_rom (soft's preset) or nearest;\n"
           "                           gaussian: the pcf channel's only (the others stay bilinear)\n"
           "  --pcf-pattern P          disk (default: k taps uniform over the filter disk, unbiased for the exact disk\n"
           "                           mean the reference is) or rotated (the paper's Poisson disk, rotated per pixel)\n"
           "  --seed N                 ensemble member: moves every random stream of the signals (default 0)\n"
           "  --fps F                  animation frames per second of scene time (default 30)\n"
           "  --shadow-map-size S      sun and lamp shadow maps, S x S texels (default 512)\n"
           "  --pcf-radius R           PCF disk radius in sun shadow-map texels (default 3)\n"
           "  --static-camera          keep the camera still (the torus still moves)\n"
           "  --frozen-mirror-view     the mirror sphere reflects as seen from frame 0's eye, whatever the camera\n"
           "                           does (signals and reference alike): env without its view dependence, to\n"
           "                           measure how much of env's error that is (README.md, \"What held env back\")\n"
           "  --light-speed DEG        the moving light: the sun and the environment map turn DEG degrees a frame\n"
           "                           about the vertical axis (default 0: fixed; the area lamp never moves)\n"
           "  --no-object-id           do not give rrc the G-buffer's per-pixel object ids (default: given, so a hit\n"
           "                           also needs every previous-depth tap to show the pixel's object; see README.md)\n"
           "  --no-images              write only summary.md, summary.csv and errors.csv\n"
           + device_options_help("rrc-sample");
}

Options parse_options(int argc, const char* const* argv) {
    Options o;
    // The signals whose channel gets the lag detector; not given: the presets' (channel_presets.h).
    std::optional<uint32_t> antilag;
    float antilag_gamma = 0.0f, antilag_threshold = 0.0f;
    // The signals whose channel gets the blur bound; not given: the presets' (channel_presets.h).
    std::optional<uint32_t> blur_bound;
    float blur_bound_px2 = 0.0f;
    // The signals whose channel gets the deviation gate; not given: the presets'.
    std::optional<uint32_t> gate;
    float gate_kappa = 0.0f;
    // --no-base picks the presets every other option then changes: read it first.
    for (int i = 1; i < argc; ++i)
        if (std::strcmp(argv[i], "--no-base") == 0) o.base = false;
    if (!o.base) o.channels = ChannelPresets(false), o.pcf_base = 0, o.env_base = 0;
    rrc_host::ArgCursor c(argc, argv);
    while (c.next()) {
        if (c.flag("--no-base"))
            continue;  // read above
        else if (c.option("--scene"))
            o.scene = scene_name(c);
        else if (c.option("--frames"))
            o.frames = (int)c.integer(1, 100000);
        else if (c.option("--size"))
            c.size(o.width, o.height, 8, 8192);
        else if (c.option("--out"))
            o.out = c.value();
        else if (c.option("--reference-every"))
            o.reference_every = (int)c.integer(0, 100000);
        else if (c.option("--reference-samples"))
            o.reference_samples = (int)c.integer(1, 65536);
        else if (c.option("--taps"))
            o.taps = (int)c.integer(1, 64);
        else if (c.option("--signals"))
            o.signals = signal_bits(c);
        else if (c.option("--reproject"))
            o.reprojection = c.choice(rrc_host::kReprojectionNames);
        else if (c.option("--depth-test"))
            o.depth_test = (uint32_t)c.choice(kDepthTestNames);
        else if (c.option("--epsilon-scale"))
            o.epsilon_scale = c.number(0.0f, 1e9f);
        else if (c.option("--soft-prior"))
            o.soft_prior = c.number(0.0f, 1e6f);
        else if (c.option("--soft-age-cap"))
            o.channels.soft.age_cap = (uint32_t)c.integer(1, RRC_MAX_AGE_CAP);
        else if (c.option("--lambda"))
            o.channels.pcf.lambda = o.channels.env.lambda = c.number(0.0f, 0.9999f);
        else if (c.option("--rectify")) {
            const float g = c.number(0.0f, RRC_MAX_RECTIFY_GAMMA);
            for (ChannelSettings* ch : {&o.channels.pcf, &o.channels.env}) {
                ch->rectify = g > 0.0f ? 1u : 0u;
                ch->rectify_gamma = g == RRC_DEFAULT_RECTIFY_GAMMA ? 0.0f : g;
            }
        } else if (c.option("--antilag"))
            antilag = signal_bits_or_none(c);
        else if (c.option("--blur-bound"))
            blur_bound = signal_bits_or_none(c);
        else if (c.option("--blur-bound-px2"))
            blur_bound_px2 = c.number(1e-6f, RRC_MAX_BLUR_BOUND);
        else if (c.option("--gate"))
            gate = signal_bits_or_none(c);
        else if (c.option("--gate-kappa"))
            gate_kappa = c.number(1e-6f, RRC_MAX_GATE_KAPPA);
        else if (c.option("--env-view-lobe")) {
            o.channels.env.view_lobe = c.number(0.0f, RRC_MAX_VIEW_LOBE);
            o.env_view_lobe_px = 0.0f;
        } else if (c.option("--env-view-lobe-px")) {
            o.env_view_lobe_px = c.number(0.0f, 1e4f);
            o.channels.env.view_lobe = 0.0f;
        }
        else if (c.option("--antilag-gamma"))
            antilag_gamma = c.number(0.0f, RRC_MAX_ANTILAG_GAMMA);
        else if (c.option("--antilag-threshold"))
            antilag_threshold = c.number(0.0f, RRC_MAX_ANTILAG_THRESHOLD);
        else if (c.option("--pcf-fill"))
            o.channels.pcf.fill_age = (uint32_t)c.integer(0, RRC_MAX_AGE_CAP + 1);
        else if (c.option("--env-fill"))
            o.channels.env.fill_age = (uint32_t)c.integer(0, RRC_MAX_AGE_CAP + 1);
        else if (c.option("--soft-lambda"))
            o.channels.soft.lambda = c.number(0.0f, 0.9999f);
        else if (c.option("--env-residual")) {
            o.env_base = c.choice(kEnvBaseNames);
            o.channels.env.residual = o.env_base != 0 ? 1u : 0u;
        } else if (c.option("--pcf-residual")) {
            o.pcf_base = (uint32_t)c.integer(0, kMaxPcfBaseTaps);
            o.channels.pcf.residual = o.pcf_base != 0 ? 1u : 0u;
        } else if (c.option("--soft-residual"))
            o.channels.soft.residual = c.choice(kOnOffNames);
        else if (c.option("--blend"))
            o.channels.pcf.blend = o.channels.env.blend = c.choice(rrc_host::kBlendNames);
        else if (c.option("--history-filter")) {
            const rrc_history_filter f = c.choice(rrc_host::kHistoryFilterNames);
            o.channels.pcf.filter = f;
            // GAUSSIAN is the pcf channel's only (the amortized-PCF chapter's blur): the others keep theirs.
            if (f != RRC_HISTORY_FILTER_GAUSSIAN) o.channels.env.filter = o.channels.soft.filter = f;
        } else if (c.option("--pcf-pattern"))
            o.pcf_pattern = c.choice(kPcfPatternNames);
        else if (c.option("--seed"))
            o.seed = (uint32_t)c.integer(0, 65535);
        else if (c.option("--fps"))
            o.fps = c.number(0.1f, 10000.0f);
        else if (c.option("--shadow-map-size"))
            o.sun_map = o.lamp_map = (uint32_t)c.integer(16, 8192);
        else if (c.option("--pcf-radius"))
            o.pcf_radius = c.number(0.0f, 64.0f);
        else if (c.option("--soft-fill"))
            o.channels.soft.fill_age = (uint32_t)c.integer(0, RRC_MAX_AGE_CAP + 1);
        else if (c.option("--fill-radius"))
            o.fill_radius = (uint32_t)c.integer(0, RRC_MAX_FILL_RADIUS);
        else if (c.option("--pcf-fill-radius"))
            o.pcf_fill_radius = (int)c.integer(0, RRC_MAX_FILL_RADIUS);
        else if (c.option("--fill-depth-tolerance"))
            o.fill_depth_tolerance = c.number(0.0f, 1e6f);
        else if (c.option("--fill-prior"))
            o.fill_prior = c.number(0.0f, 1e6f);
        else if (c.option("--blur-sigma"))
            o.channels.pcf.blur_sigma = c.number(0.0f, RRC_MAX_BLUR_SIGMA);
        else if (c.option("--pcf-smoothstep")) {
            const std::vector<float> e = c.numbers(-1e6f, 1e6f);
            if (e.size() != 2 || !(e[1] > e[0])) c.fail("expected E0,E1 with E0 < E1");
            o.pcf_smooth_e0 = e[0];
            o.pcf_smooth_e1 = e[1];
            o.pcf_smoothstep = true;
        } else if (c.option("--pcf-threshold"))
            o.pcf_threshold = c.number(0.0f, 1.0f);
        else if (c.flag("--pcf-confidence"))
            o.channels.pcf.confidence = 1;
        else if (c.option("--reference-frames"))
            for (long f : c.integers(0, 100000)) o.reference_frames.push_back((int)f);
        else if (c.flag("--dump-soft"))
            o.dump_soft = true;
        else if (c.option("--young-ages"))
            o.young_ages = (uint32_t)c.integer(1, 255);
        else if (c.flag("--static-camera"))
            o.static_camera = true;
        else if (c.flag("--frozen-mirror-view"))
            o.frozen_mirror_view = true;
        else if (c.option("--light-speed"))
            o.light_speed = c.number(-180.0f, 180.0f);
        else if (c.flag("--no-object-id"))
            o.object_id = false;
        else if (c.flag("--no-images"))
            o.write_images = false;
        else if (!device_option(c, o.validation, o.device, o.quiet))
            c.unknown();
    }
    o.check_options = c.check_only();
    o.help = c.help();
    if (o.channels.pcf.blur_sigma > 0.0f && o.channels.pcf.filter != RRC_HISTORY_FILTER_GAUSSIAN)
        throw OptionError("--blur-sigma needs --history-filter gaussian");
    // The fill's fallback is the PCSS estimate, worth --fill-prior samples; without a fill rrc takes none.
    // The fill's members go to rrc only with a fill (the library refuses them without one).
    const bool fill = o.channels.soft.fill_age != 0;
    o.channels.soft.fill_prior = !fill ? 0.0f : o.fill_prior >= 0.0f ? o.fill_prior : o.channels.soft.fill_prior;
    o.channels.soft.fill_radius = fill ? o.fill_radius : 0u;
    o.channels.soft.fill_depth_tolerance = fill ? o.fill_depth_tolerance : 0.0f;
    // pcf's window: the preset's unless given; rrc refuses a window without a fill, so --pcf-fill 0
    // leaves it at 0 and refuses one given.
    if (o.channels.pcf.fill_age == 0 && o.pcf_fill_radius > 0) throw OptionError("--pcf-fill-radius needs the pcf fill (--pcf-fill T > 0)");
    const ChannelPresets presets(o.base);
    o.channels.pcf.fill_radius = o.channels.pcf.fill_age == 0 ? 0u
                                 : o.pcf_fill_radius >= 0  ? (uint32_t)o.pcf_fill_radius
                                                           : presets.pcf.fill_radius;
    // Not given, --antilag keeps the presets' channels and constants (--antilag-gamma/-threshold
    // override them); given, the listed channels get the given constants or the library's.
    uint32_t preset_bits = 0;
    for (auto [bit, ch] : {std::pair<uint32_t, const ChannelSettings*>{kSignalPcf, &presets.pcf}, {kSignalEnv, &presets.env},
                           {kSignalSoft, &presets.soft}})
        if (ch->antilag) preset_bits |= bit;
    const uint32_t antilag_bits = antilag ? *antilag : preset_bits;
    if (antilag_bits == 0 && (antilag_gamma > 0.0f || antilag_threshold > 0.0f))
        throw OptionError("--antilag-gamma and --antilag-threshold need --antilag");
    for (auto [bit, ch] : {std::pair<uint32_t, ChannelSettings*>{kSignalPcf, &o.channels.pcf}, {kSignalEnv, &o.channels.env},
                           {kSignalSoft, &o.channels.soft}}) {
        const bool from_preset = !antilag && ch->antilag;
        ch->antilag = (antilag_bits & bit) ? 1u : 0u;
        ch->antilag_gamma = !ch->antilag ? 0.0f : antilag_gamma > 0.0f ? antilag_gamma : from_preset ? ch->antilag_gamma : 0.0f;
        ch->antilag_threshold = !ch->antilag            ? 0.0f
                                : antilag_threshold > 0.0f ? antilag_threshold
                                : from_preset             ? ch->antilag_threshold
                                                          : 0.0f;
    }
    // Not given, --blur-bound keeps the presets' channels and B (--blur-bound-px2 overrides it);
    // given, the listed channels get the given B or kSampleBlurBound.
    uint32_t preset_bound_bits = 0;
    for (auto [bit, ch] : {std::pair<uint32_t, const ChannelSettings*>{kSignalPcf, &presets.pcf}, {kSignalEnv, &presets.env},
                           {kSignalSoft, &presets.soft}})
        if (ch->blur_bound > 0.0f) preset_bound_bits |= bit;
    const uint32_t bound_bits = blur_bound ? *blur_bound : preset_bound_bits;
    if (bound_bits == 0 && blur_bound_px2 > 0.0f) throw OptionError("--blur-bound-px2 needs --blur-bound");
    for (auto [bit, ch] : {std::pair<uint32_t, ChannelSettings*>{kSignalPcf, &o.channels.pcf}, {kSignalEnv, &o.channels.env},
                           {kSignalSoft, &o.channels.soft}}) {
        const bool from_preset = !blur_bound && ch->blur_bound > 0.0f;
        ch->blur_bound = !(bound_bits & bit)       ? 0.0f
                         : blur_bound_px2 > 0.0f  ? blur_bound_px2
                         : from_preset            ? ch->blur_bound
                                                  : kSampleBlurBound;
    }
    // Not given, --gate keeps the presets' channels and kappa (--gate-kappa overrides it); given,
    // the listed channels get the given kappa or kSampleGateKappa.
    uint32_t preset_gate_bits = 0;
    for (auto [bit, ch] : {std::pair<uint32_t, const ChannelSettings*>{kSignalPcf, &presets.pcf}, {kSignalEnv, &presets.env},
                           {kSignalSoft, &presets.soft}})
        if (ch->gate_kappa > 0.0f) preset_gate_bits |= bit;
    const uint32_t gate_bits = gate ? *gate : preset_gate_bits;
    if (gate_bits == 0 && gate_kappa > 0.0f) throw OptionError("--gate-kappa needs --gate");
    for (auto [bit, ch] : {std::pair<uint32_t, ChannelSettings*>{kSignalPcf, &o.channels.pcf}, {kSignalEnv, &o.channels.env},
                           {kSignalSoft, &o.channels.soft}}) {
        const bool from_preset = !gate && ch->gate_kappa > 0.0f;
        ch->gate_kappa = !(gate_bits & bit)   ? 0.0f
                         : gate_kappa > 0.0f ? gate_kappa
                         : from_preset       ? ch->gate_kappa
                                             : kSampleGateKappa;
        // rrc refuses the gate on a channel with confidence: say so here, by option name.
        if (ch->gate_kappa > 0.0f && ch->confidence) throw OptionError("--gate: the pcf channel has --pcf-confidence, which the gate refuses");
    }
    // rrc refuses ADAPTIVE with an epsilon (rrc.h, rrc_context_desc.depth_test): say so here, by option name.
    if (o.depth_test == RRC_DEPTH_TEST_ADAPTIVE && o.epsilon_scale > 0.0f)
        throw OptionError("--depth-test adaptive takes no --epsilon-scale (an epsilon makes the test fixed)");
    return o;
}

}  // namespace rrc_sample
