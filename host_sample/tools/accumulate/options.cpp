// rrc-accumulate: command-line parsing.
#include "options.h"

#include "enum_names.h"
#include "options_parser.h"

#include <algorithm>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <stdexcept>
#include <sstream>

namespace rrc_cli {

namespace {

// Strict number parsing: the whole text, finite unless allow_inf.
bool parse_float(const std::string& text, float& out, bool allow_inf = false) {
    if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
    errno = 0;
    char* end = nullptr;
    double v = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || std::isnan(v)) return false;
    if (std::isinf(v) && !(allow_inf && v > 0 && errno == 0)) return false;
    if (!std::isinf(v) && std::fabs(v) > 3.4028234663852886e38) return false;
    out = static_cast<float>(v);
    return true;
}

bool parse_int(const std::string& text, int64_t& out) {
    if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) return false;
    errno = 0;
    char* end = nullptr;
    long long v = std::strtoll(text.c_str(), &end, 10);
    if (errno == ERANGE || end != text.c_str() + text.size()) return false;
    out = v;
    return true;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// "a,b,c" -> {"a","b","c"}; false if an item is empty.
bool split_list(const std::string& text, std::vector<std::string>& out) {
    out.clear();
    std::size_t pos = 0;
    while (true) {
        std::size_t comma = text.find(',', pos);
        out.push_back(text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
        if (out.back().empty()) return false;
        if (comma == std::string::npos) return true;
        pos = comma + 1;
    }
}

using rrc_host::EnumName;

constexpr EnumName<Reproject> kReprojectNames[] = {
    {"prev_clip", Reproject::PrevClip}, {"motion", Reproject::Motion}, {"camera", Reproject::Camera}};
constexpr EnumName<MotionUnits> kMotionUnitNames[] = {{"uv", MotionUnits::Uv}, {"pixels", MotionUnits::Pixels}};
constexpr EnumName<Progress> kProgressNames[] = {{"auto", Progress::Auto}, {"bar", Progress::Bar}, {"lines", Progress::Lines}};
// --depth-test: the library's choices (rrc.h, rrc_context_desc.depth_test).
constexpr EnumName<rrc_depth_test> kDepthTestNames[] = {
    {"default", RRC_DEPTH_TEST_DEFAULT}, {"adaptive", RRC_DEPTH_TEST_ADAPTIVE}, {"fixed", RRC_DEPTH_TEST_FIXED}};

// The layers that carry the per-pixel geometry or our own output.
bool is_reserved_layer(const std::string& layer) { return layer == "mv" || layer == "prevclip" || layer == "nocache" || layer == "rrc"; }

}  // namespace

std::string metrics_path(const Options& o) {
    if (!o.metrics_file.empty()) return o.metrics_file;
    const std::size_t slash = o.output_pattern.find_last_of('/');
    return slash == std::string::npos ? std::string("metrics.csv") : o.output_pattern.substr(0, slash + 1) + "metrics.csv";
}

const char* reproject_name(Reproject r) { return rrc_host::enum_name(kReprojectNames, r); }

const char* depth_mode_name(rrc_depth_mode m) { return rrc_host::enum_name(rrc_host::kDepthModeNames, m); }

const char* depth_test_name(rrc_depth_test t) { return rrc_host::enum_name(kDepthTestNames, t); }

rrc_channel_desc blender_preset_channel() {
    rrc_channel_desc d{RRC_STRUCT_TYPE_CHANNEL_DESC, nullptr, sizeof d};
    if (rrc_channel_preset(RRC_PRESET_OFFLINE, 0, RRC_API_VERSION, &d) != RRC_SUCCESS)
        throw std::runtime_error(std::string("rrc_channel_preset: ") + rrc_last_error());
    return d;
}

rrc_context_desc blender_preset_context(uint32_t width, uint32_t height) {
    rrc_context_desc d{RRC_STRUCT_TYPE_CONTEXT_DESC, nullptr, sizeof d, RRC_API_VERSION, width, height};
    if (rrc_context_preset(RRC_PRESET_OFFLINE, 0, RRC_API_VERSION, &d) != RRC_SUCCESS)
        throw std::runtime_error(std::string("rrc_context_preset: ") + rrc_last_error());
    return d;
}

float blender_preset_tau() { return blender_preset_context(1, 1).tau; }

SignalOptions blender_preset_signal(const std::string& layer) {
    const rrc_channel_desc d = blender_preset_channel();
    SignalOptions s;
    s.layer = layer;
    s.lambda = d.lambda;
    s.blend = d.blend;
    s.filter = d.filter;
    s.fill_age = d.fill_age;
    s.rectify = d.rectify;
    s.gate_kappa = d.gate_kappa;
    return s;
}

bool parse_signal_spec(const std::string& text, SignalOptions& out, std::string& error) {
    SignalOptions s;
    const std::size_t colon = text.find(':');
    s.layer = text.substr(0, colon);
    const std::string where = "--signal " + quoted(text) + ": ";
    if (s.layer.empty()) {
        error = where + "the layer name is empty";
        return false;
    }
    if (s.layer.size() >= RRC_MAX_NAME) {
        error = where + "the layer name is longer than " + std::to_string(RRC_MAX_NAME - 1) + " characters";
        return false;
    }
    if (s.layer.front() == '.' || s.layer.back() == '.' || s.layer.find('=') != std::string::npos ||
        s.layer.find(',') != std::string::npos) {
        error = where + "invalid layer name " + quoted(s.layer);
        return false;
    }
    if (is_reserved_layer(s.layer)) {
        error = where + "layer " + quoted(s.layer) + " is reserved (mv, prevclip, nocache, rrc)";
        return false;
    }
    std::set<std::string> seen;
    // key=value naming one of `table`'s values into `field`.
    auto choose = [&](const std::string& key, const auto& table, auto& field, const std::string& value) {
        if (rrc_host::enum_value(table, value, field)) return true;
        error = where + key + " must be " + rrc_host::enum_choices(table) + ", got " + quoted(value);
        return false;
    };
    if (colon != std::string::npos) {
        std::string rest = text.substr(colon + 1);
        if (rest.empty()) {
            error = where + "nothing after ':' (expected key=value,...)";
            return false;
        }
        std::size_t pos = 0;
        while (pos <= rest.size()) {
            std::size_t comma = rest.find(',', pos);
            std::string item = rest.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
            pos = comma == std::string::npos ? rest.size() + 1 : comma + 1;
            std::size_t eq = item.find('=');
            if (item.empty() || eq == std::string::npos || eq == 0 || eq + 1 == item.size()) {
                error = where + "expected key=value, got " + quoted(item);
                return false;
            }
            std::string key = item.substr(0, eq), value = item.substr(eq + 1);
            if (!seen.insert(key).second) {
                error = where + "'" + key + "' given twice";
                return false;
            }
            if (key == "lambda") {
                if (!parse_float(value, s.lambda) || !(s.lambda >= 0.0f && s.lambda < 1.0f)) {
                    error = where + "lambda must be a number in [0, 1), got " + quoted(value);
                    return false;
                }
            } else if (key == "blend" || key == "filter" || key == "history") {
                const bool ok = key == "blend"    ? choose(key, rrc_host::kBlendNames, s.blend, value)
                                : key == "filter" ? choose(key, rrc_host::kHistoryFilterNames, s.filter, value)
                                                  : choose(key, rrc_host::kHistoryPrecisionNames, s.history, value);
                if (!ok) return false;
            } else if (key == "max_age") {
                int64_t v = 0;
                if (!parse_int(value, v) || v < 1 || v > static_cast<int64_t>(RRC_MAX_AGE_CAP)) {
                    error = where + "max_age must be an integer in [1, " + std::to_string(RRC_MAX_AGE_CAP) + "], got " + quoted(value);
                    return false;
                }
                s.max_age = static_cast<uint32_t>(v);
            } else if (key == "fill" || key == "fill_radius") {
                const int64_t hi = key == "fill" ? static_cast<int64_t>(RRC_MAX_AGE_CAP) + 1 : static_cast<int64_t>(RRC_MAX_FILL_RADIUS);
                int64_t v = 0;
                if (!parse_int(value, v) || v < 1 || v > hi) {
                    error = where + key + " must be an integer in [1, " + std::to_string(hi) + "], got " + quoted(value);
                    return false;
                }
                (key == "fill" ? s.fill_age : s.fill_radius) = static_cast<uint32_t>(v);
            } else if (key == "fill_tolerance") {
                if (!parse_float(value, s.fill_depth_tolerance) || !(s.fill_depth_tolerance > 0.0f && s.fill_depth_tolerance <= 1.0f)) {
                    error = where + "fill_tolerance must be a number in (0, 1], got " + quoted(value);
                    return false;
                }
            } else if (key == "rectify" || key == "antilag") {
                if (value != "on" && value != "off") {
                    error = where + key + " must be on or off, got " + quoted(value);
                    return false;
                }
                (key == "rectify" ? s.rectify : s.antilag) = value == "on" ? 1u : 0u;
            } else if (key == "rectify_gamma" || key == "antilag_gamma" || key == "antilag_threshold" || key == "blur_bound" ||
                       key == "gate") {
                // Each in (0, its maximum]: the library's own range (include/rrc/rrc.h), checked here so that
                // a typo fails before any file is read.
                const float hi = key == "rectify_gamma"   ? RRC_MAX_RECTIFY_GAMMA
                                 : key == "antilag_gamma" ? RRC_MAX_ANTILAG_GAMMA
                                 : key == "blur_bound"    ? RRC_MAX_BLUR_BOUND
                                 : key == "gate"          ? RRC_MAX_GATE_KAPPA
                                                          : RRC_MAX_ANTILAG_THRESHOLD;
                float& field = key == "rectify_gamma"   ? s.rectify_gamma
                               : key == "antilag_gamma" ? s.antilag_gamma
                               : key == "blur_bound"    ? s.blur_bound
                               : key == "gate"          ? s.gate_kappa
                                                        : s.antilag_threshold;
                if (!parse_float(value, field) || !(field > 0.0f && field <= hi)) {
                    char range[32];
                    std::snprintf(range, sizeof range, "(0, %g]", static_cast<double>(hi));
                    error = where + key + " must be a number in " + range + ", got " + quoted(value);
                    return false;
                }
            } else {
                error = where + "unknown key " + quoted(key) +
                        " (expected lambda, blend, filter, history, max_age, fill, fill_radius, fill_tolerance, rectify, "
                        "rectify_gamma, antilag, antilag_gamma, antilag_threshold, blur_bound, gate)";
                return false;
            }
        }
    }
    if ((s.fill_radius != 0 || s.fill_depth_tolerance != 0.0f) && s.fill_age == 0) {
        error = where + (s.fill_radius != 0 ? "fill_radius" : "fill_tolerance") + std::string(" needs fill=T");
        return false;
    }
    if (s.rectify_gamma != 0.0f && !s.rectify) {
        error = where + "rectify_gamma needs rectify=on";
        return false;
    }
    if ((s.antilag_gamma != 0.0f || s.antilag_threshold != 0.0f) && !s.antilag) {
        error = where + (s.antilag_gamma != 0.0f ? "antilag_gamma" : "antilag_threshold") + std::string(" needs antilag=on");
        return false;
    }
    if (s.fill_age > s.max_age + 1) {
        error = where + "fill (" + std::to_string(s.fill_age) + ") must be at most max_age + 1 (" + std::to_string(s.max_age + 1) + ")";
        return false;
    }
    out = s;
    return true;
}

bool parse_frame_range(const std::string& text, int64_t& first, int64_t& last, std::string& error) {
    const std::string where = "--frames " + quoted(text) + ": ";
    const std::size_t dash = text.find('-');
    int64_t a = 0, b = 0;
    bool ok = dash == std::string::npos ? parse_int(text, a) && (b = a, true)
                                        : parse_int(text.substr(0, dash), a) && parse_int(text.substr(dash + 1), b);
    if (!ok) {
        error = where + "expected FIRST-LAST or FRAME with non-negative integers (e.g. 1-24)";
        return false;
    }
    if (b < a) {
        error = where + "the last frame is before the first";
        return false;
    }
    if (b > 999999999) {
        error = where + "frame numbers above 999999999 are not supported";
        return false;
    }
    first = a;
    last = b;
    return true;
}

namespace {

// Walks a pattern; calls lit(text) for literal text and conv(zero_pad, width)
// for the integer conversion.  Returns the number of conversions or -1.
template <class Lit, class Conv>
int walk_pattern(const std::string& p, Lit lit, Conv conv, std::string& bad) {
    int conversions = 0;
    for (std::size_t i = 0; i < p.size();) {
        if (p[i] != '%') {
            std::size_t j = p.find('%', i);
            lit(p.substr(i, j == std::string::npos ? std::string::npos : j - i));
            i = j == std::string::npos ? p.size() : j;
            continue;
        }
        std::size_t j = i + 1;
        if (j < p.size() && p[j] == '%') {
            lit("%");
            i = j + 1;
            continue;
        }
        bool zero = false;
        if (j < p.size() && p[j] == '0') {
            zero = true;
            ++j;
        }
        int width = 0;
        while (j < p.size() && std::isdigit(static_cast<unsigned char>(p[j])) && width < 100) width = width * 10 + (p[j++] - '0');
        if (j >= p.size() || (p[j] != 'd' && p[j] != 'i' && p[j] != 'u') || width > 32) {
            bad = p.substr(i, j < p.size() ? j - i + 1 : std::string::npos);
            return -1;
        }
        conv(zero, width);
        ++conversions;
        i = j + 1;
    }
    return conversions;
}

}  // namespace

bool validate_pattern(const std::string& pattern, std::string& error) {
    std::string bad;
    int n = walk_pattern(
        pattern, [](const std::string&) {}, [](bool, int) {}, bad);
    if (pattern.empty())
        error = "the pattern is empty";
    else if (n < 0)
        error = "unsupported conversion " + quoted(bad) + " in " + quoted(pattern) + " (use %d, %04d...; write %% for a literal %)";
    else if (n != 1)
        error = quoted(pattern) + " must contain exactly one frame-number conversion such as %04d, found " + std::to_string(n);
    else
        return true;
    return false;
}

std::string format_frame_path(const std::string& pattern, int64_t frame) {
    std::string out, bad;
    walk_pattern(
        pattern, [&](const std::string& s) { out += s; },
        [&](bool zero, int width) {
            std::string digits = std::to_string(frame < 0 ? -frame : frame);
            std::string sign = frame < 0 ? "-" : "";
            const std::size_t len = digits.size() + sign.size();
            const std::size_t pad = static_cast<std::size_t>(width) > len ? width - len : 0;
            out += zero ? sign + std::string(pad, '0') + digits : std::string(pad, ' ') + sign + digits;
        },
        bad);
    return out;
}

std::string usage_text() {
    std::string text = R"(Usage: rrc-accumulate --input PATTERN --frames A-B --output PATTERN [options]

Accumulates a numbered sequence of OpenEXR frames (single- or multi-part,
half, float or uint channels) with rrc, the real-time reprojection cache,
and writes one OpenEXR per frame.  Renderer passes are read by channel name:
the project's own names by default, Blender's with --preset blender, any
other through the channel options.  docs/guide/offline.md is the guide;
docs/measurements/OFFLINE.md has every pass and convention, measured.

Required:
  --input PATTERN        input frames, printf-style: frames/f_%04d.exr
  --frames A-B           inclusive frame range (or a single frame A); may start
                         anywhere: the first frame processed is a full miss
  --output PATTERN       output frames: out/acc_%04d.exr (directories are
                         created; an output may never be one of the inputs)

Presets:
  --preset blender       Blender 3.x OpenEXR MultiLayer (Cycles passes
                         Combined, Z and Vector): depth <view layer>.Depth.Z as
                         linear (planar) view depth with the sky at 1e10,
                         motion <view layer>.Vector.X/.Y (previous minus
                         current position, pixels, y up; .Z/.W, the next
                         frame's, are not used), --tau @TAU@, the object ids
                         <view layer>.IndexOB.X when the first frame has them
                         (the Object Index pass; without it the run goes
                         without ids, and says so), and the signal
                         <view layer>.Combined when no --signal is given,
                         accumulated with
                         @PRESET_SIGNAL@
                         (chosen from the error against render time
                         measured on Cycles sequences, docs/measurements/OFFLINE.md
                         section 7; an explicit --signal has the defaults
                         below).
                         Every option given explicitly overrides the preset.
  --view-layer NAME      the view layer to read (found when there is one)

Geometry and the hit test:
  --depth-mode M         standard (NDC, near 0; default) | reversed (NDC,
                         near 1) | linear (view depth)
  --depth-format F       float32 (default) | unorm16 | unorm24: the depth
                         buffer's format, which sets epsilon
  --epsilon E            absolute epsilon for NDC depth (overrides the format)
  --epsilon-scale S      epsilon = S x the format's smallest increment
                         (default 4 for float32, 1 for unorm)
  --tau T                relative tolerance for linear-depth tests (0.01;
                         @TAU@ with --preset blender)
  --background-threshold T  linear depth >= T is background (1e10)
  --depth-test T         default | adaptive | fixed: the library's hit test.
                         default: adaptive unless --epsilon, --epsilon-scale
                         or --tau is given (or set by --preset), fixed then;
                         fixed: the paper's |diff| <= eps (or tau x depth);
                         adaptive: eps plus a bound on the bilinear residual,
                         for the NDC modes' exact tests (prev_clip, motion
                         with mv.Z, camera); linear depth and plain motion
                         use tau x depth under both.  adaptive cannot be
                         combined with --epsilon, --epsilon-scale, --tau or
                         --preset blender (which sets --tau)
  --near N, --far F      view distances of the near and far planes (F may be
                         inf); needed by --reproject motion on NDC depth
                         without mv.Z
  --reproject R          prev_clip (default) | motion | camera
                           prev_clip: channels prevclip.X/.Y/.Z/.W
                           motion: mv.X, mv.Y (uv_prev - uv_cur); with an mv.Z
                             channel in the first frame (expected previous
                             depth - current depth) the exact depth test is used
                           camera: view_proj matrices from --camera (static
                             scenes only)
  --motion-units U       uv (default) | pixels: the unit of the motion vectors
  --motion-y Y           down (default: rows grow downwards, as rrc) | up
                         (as Blender): the direction of the vectors' y
  --motion-scale SX,SY   multiplies the vectors after the units and y sign are
                         applied (1,1): e.g. -1,-1 for current minus previous
  --camera FILE          JSON object: frame number (string) ->
                         {"view_proj": [16 numbers, column-major as GLM, Vulkan
                         clip], "jitter": [x, y] (pixels, optional)}.  Required
                         by --reproject camera; otherwise read for jitter only
  --cut F[,F...]         camera cuts: frame F starts a new shot and every pixel
                         misses (renderers' vectors are not reset at cuts);
                         repeatable

Channel names (any channel of the file can be mapped):
  --depth-channel NAME          depth (Z)
  --motion-channels X,Y[,Z]     motion vectors (mv.X,mv.Y[,mv.Z]); a third
                                channel is the depth change
  --prevclip-channels X,Y,Z,W   previous clip positions (prevclip.X,...)
  --nocache-channel NAME        do-not-cache mask (nocache.Y)
  --object-id NAME              per-pixel object ids (none by default;
                                <view layer>.IndexOB.X with --preset blender
                                when present): a hit then also needs every
                                previous depth tap of non-zero bilinear weight
                                to carry the pixel's id.  A float channel
                                (Blender's IndexOB) is rounded to the nearest
                                integer; negative, non-finite or values above
                                4294967295 are an error naming the pixel.
                                A UINT channel is read exactly
  --no-object-id                read no object ids (not even the preset's)

Signals:
  --signal NAME[:key=value,...]   accumulate EXR layer NAME (repeatable, at
                         most 4).  Keys: lambda=0.6 (history weight, [0,1)),
                         blend=fixed|age_aware|running_mean (fixed),
                         filter=nearest|bilinear|catmull_rom|gaussian (bilinear),
                         history=fp16|fp32 (fp16), max_age=1..65535 (255),
                         fill=T (off): pixels younger than T samples are
                         shown as a depth-aware mean of their neighbours'
                         histories (docs/CONVENTIONS.md, "The spatial
                         fill"; display only: the history keeps its own
                         samples), fill_radius=1..4 (2: a 5x5 window),
                         fill_tolerance=(0,1] (0.005: the relative depth
                         difference at which a neighbour still counts).
                         The cures for error under motion (off; see
                         docs/CONVENTIONS.md for each): rectify=on|off
                         (clamp the history to this frame's 3x3
                         neighbourhood, "Rectification"), rectify_gamma=
                         (0,16] (1: the box's half width in sigmas);
                         antilag=on|off (shorten the history where it
                         left that box, "The lag detector"),
                         antilag_gamma=(0,16] (2), antilag_threshold=
                         (0,2] (0.5: the relative gap that drops the
                         history); blur_bound=(0,64] px^2 (off: cap the
                         history's age so that its resampling blur stays
                         within B px^2 per axis, "The blur bound");
                         gate=(0,16] (off: cut the history's age where its
                         bias, the mean of sample - history, exceeds kappa
                         standard errors, "The deviation gate").
                         Without --signal every layer of the first frame is
                         accumulated except the depth, motion, prevclip and
                         nocache channels' layers.  A layer is NAME.Y (or any
                         single channel NAME.c: one component) or
                         NAME.R/.G/.B[/.A] (four components; a missing A is
                         given as 1 and not written back); NAME may hold dots
                         (ViewLayer.Combined).  A NAME.conf channel is a
                         per-sample confidence in [0,1].

Other inputs (optional):
  nocache.Y channel      non-zero: the pixel is never a hit ("do not cache")
  --object-id channel    the object ids (above)
  jitter in --camera     the frame's sub-pixel offset, pixels, x right y down

Measurements and pictures:
  --reference PATTERN    converged frames (same channel names as the signals)
                         to measure against: per frame and signal the RMSE and
                         PSNR of the raw input and of the accumulated output
                         go to a CSV file, and a summary line is printed
  --metrics FILE         the CSV file (default: metrics.csv in the output
                         directory)
  --psnr-peak P          PSNR = 10 log10(P^2 / MSE) (1)
  --coherence PATTERN    a PNG per frame: green hit, red miss, blue refreshed,
                         dark grey background, magenta invalid geometry
  --clean-report FILE    what rrc adds to a clean input: per frame and signal
                         the accumulated output against that frame's own input,
                         RMSE over all pixels and by region (background, edge,
                         filled, miss, young, history; docs/measurements/OFFLINE.md, "What
                         rrc adds to a clean input"), each with its share of
                         the squared error and of the pixels; FILE ending in
                         .md gets the summary tables, in .csv the rows per
                         frame; the summary is also printed
  --from N               the --clean-report summary's first frame (8; the
                         range's first when it ends before frame 8)

Device and output:
  --device NAME          the first Vulkan device whose name contains NAME
  --validation           enable the Khronos validation layer (as does
                         RRC_VALIDATION=1); any message makes the exit
                         status non-zero
  --progress P           auto (default: a progress bar with the frame count
                         and ETA on a terminal, one line per frame otherwise)
                         | bar | lines
  --quiet                no progress (the summary lines remain)
  --verbose              also print the library's informational log
  --check-options        check the options as a run would (without reading a
                         file), print "rrc-accumulate: options ok" and exit
  --help, -h             this text

Output channels (32-bit float): each layer's channels as in the input
(NAME.Y or NAME.R/G/B[/A]) holding the accumulated values, NAME.age (the
number of samples in the history, an exact integer), NAME.weight (confidence
layers only: the accumulated confidence), and rrc.mask: the integer value of
the per-pixel bitfield 1 HIT, 2 REFRESHED, 4 BACKGROUND, 8 INVALID_SAMPLE,
16 INVALID_GEOMETRY.

Images are row-major with row 0 at the top.  Every input frame's header and
block table is checked before anything is written; each output file is
written under a temporary name and renamed when complete, so an error never
leaves a partial file.  Each frame reports its number, hit ratio (hits /
(hits + misses); background excluded) and time; the last line summarises
the run.

Exit status: 0 success, 1 an error (missing, truncated or corrupt file,
missing channel, library error, validation message), 2 a bad command line.
)";
    char tau[32];
    std::snprintf(tau, sizeof tau, "%g", static_cast<double>(blender_preset_tau()));
    for (std::size_t p; (p = text.find("@TAU@")) != std::string::npos;) text.replace(p, 5, tau);
    const rrc_channel_desc preset = blender_preset_channel();
    char preset_signal[128], gate[32] = "";
    if (preset.gate_kappa > 0.0f) std::snprintf(gate, sizeof gate, ",gate=%g", static_cast<double>(preset.gate_kappa));
    std::snprintf(preset_signal, sizeof preset_signal, "lambda=%g,blend=%s,filter=%s,fill=%u,rectify=%s%s",
                  static_cast<double>(preset.lambda), rrc_host::enum_name(rrc_host::kBlendNames, preset.blend),
                  rrc_host::enum_name(rrc_host::kHistoryFilterNames, preset.filter), preset.fill_age, preset.rectify ? "on" : "off", gate);
    const std::string marker = "@PRESET_SIGNAL@";
    for (std::size_t p; (p = text.find(marker)) != std::string::npos;) text.replace(p, marker.size(), preset_signal);
    return text;
}

const std::vector<std::string>& value_options() {
    static const std::vector<std::string> names = {"--input",
                                                   "--output",
                                                   "--frames",
                                                   "--depth-mode",
                                                   "--depth-format",
                                                   "--epsilon",
                                                   "--epsilon-scale",
                                                   "--tau",
                                                   "--background-threshold",
                                                   "--near",
                                                   "--far",
                                                   "--reproject",
                                                   "--motion-scale",
                                                   "--camera",
                                                   "--signal",
                                                   "--device",
                                                   "--preset",
                                                   "--view-layer",
                                                   "--depth-channel",
                                                   "--motion-channels",
                                                   "--prevclip-channels",
                                                   "--nocache-channel",
                                                   "--object-id",
                                                   "--depth-test",
                                                   "--motion-units",
                                                   "--motion-y",
                                                   "--cut",
                                                   "--coherence",
                                                   "--reference",
                                                   "--metrics",
                                                   "--psnr-peak",
                                                   "--clean-report",
                                                   "--from",
                                                   "--progress"};
    return names;
}

namespace {

// One option that takes a value, at the cursor: its value checked into `o`; the error, or "" if none.
std::string parse_value_option(rrc_host::ArgCursor& c, Options& o) {
    const std::string arg = c.arg();
    c.option(arg.c_str());
    const std::string value = c.value();
    if (arg != "--signal" && arg != "--cut") c.once();  // the two repeatable options
    const std::string where = "option " + arg + " " + quoted(value) + ": ";

    if (arg == "--input" || arg == "--output" || arg == "--coherence" || arg == "--reference") {
        std::string err;
        if (!validate_pattern(value, err)) return "option " + arg + ": " + err;
        (arg == "--input"       ? o.input_pattern
         : arg == "--output"    ? o.output_pattern
         : arg == "--coherence" ? o.coherence_pattern
                                : o.reference_pattern) = value;
    } else if (arg == "--preset") {
        if (value != "blender") return where + "the only preset is blender (Blender 3.x multilayer EXR passes)";
        o.preset = value;
    } else if (arg == "--clean-report") {
        const bool md = value.size() > 3 && value.compare(value.size() - 3, 3, ".md") == 0;
        const bool csv = value.size() > 4 && value.compare(value.size() - 4, 4, ".csv") == 0;
        if (!md && !csv) return where + "expected a file name ending in .md or .csv";
        o.clean_report = value;
    } else if (arg == "--from") {
        int64_t f = 0;
        if (!parse_int(value, f) || f > 999999999) return where + "expected a frame number";
        o.clean_from = f;
    } else if (arg == "--view-layer" || arg == "--depth-channel" || arg == "--nocache-channel" || arg == "--metrics" ||
               arg == "--object-id") {
        if (value.empty()) return "option " + arg + ": the name is empty";
        (arg == "--view-layer"      ? o.view_layer
         : arg == "--depth-channel" ? o.depth_channel
         : arg == "--metrics"       ? o.metrics_file
         : arg == "--object-id"     ? o.object_id_channel
                                    : o.nocache_channel) = value;
    } else if (arg == "--motion-channels" || arg == "--prevclip-channels") {
        std::vector<std::string> names;
        const bool motion = arg == "--motion-channels";
        if (!split_list(value, names) || (motion ? names.size() < 2 || names.size() > 3 : names.size() != 4))
            return where + (motion ? "expected 2 or 3 channel names X,Y[,Z] (e.g. mv.X,mv.Y)"
                                   : "expected 4 channel names X,Y,Z,W (e.g. prevclip.X,...)");
        for (std::size_t a = 0; a < names.size(); ++a)
            for (std::size_t b = a + 1; b < names.size(); ++b)
                if (names[a] == names[b]) return where + "channel " + quoted(names[a]) + " named twice";
        (motion ? o.motion_channels : o.prevclip_channels) = names;
    } else if (arg == "--motion-units" || arg == "--progress" || arg == "--depth-mode" || arg == "--depth-format" ||
               arg == "--reproject" || arg == "--depth-test") {
        // One of a table's names; the message lists them.
        std::string choices;
        auto choose = [&](const auto& table, auto& field) {
            choices = rrc_host::enum_choices(table);
            return rrc_host::enum_value(table, value, field);
        };
        const bool ok = arg == "--motion-units"   ? choose(kMotionUnitNames, o.motion_units)
                        : arg == "--progress"     ? choose(kProgressNames, o.progress)
                        : arg == "--depth-mode"   ? choose(rrc_host::kDepthModeNames, o.depth_mode)
                        : arg == "--depth-format" ? choose(rrc_host::kDepthFormatNames, o.depth_format)
                        : arg == "--depth-test"   ? choose(kDepthTestNames, o.depth_test)
                                                  : choose(kReprojectNames, o.reproject);
        if (!ok) return where + "expected " + choices;
    } else if (arg == "--motion-y") {
        if (value == "down")
            o.motion_y_up = false;
        else if (value == "up")
            o.motion_y_up = true;
        else
            return where + "expected down (rows grow downwards, as rrc) or up (as Blender)";
    } else if (arg == "--cut") {
        std::vector<std::string> items;
        if (!split_list(value, items)) return where + "expected frame numbers F[,F...]";
        for (const std::string& item : items) {
            int64_t f = 0;
            if (!parse_int(item, f) || f > 999999999) return where + "expected frame numbers F[,F...], got " + quoted(item);
            o.cuts.push_back(f);
        }
    } else if (arg == "--psnr-peak") {
        float v = 0;
        if (!parse_float(value, v) || !(v > 0.0f)) return where + "expected a positive number";
        o.psnr_peak = v;
    } else if (arg == "--frames") {
        std::string err;
        if (!parse_frame_range(value, o.first_frame, o.last_frame, err)) return err;
    } else if (arg == "--epsilon" || arg == "--epsilon-scale" || arg == "--tau" || arg == "--background-threshold" || arg == "--near") {
        float v = 0;
        if (!parse_float(value, v) || !(v > 0.0f)) return where + "expected a positive number";
        (arg == "--epsilon"         ? o.epsilon
         : arg == "--epsilon-scale" ? o.epsilon_scale
         : arg == "--tau"           ? o.tau
         : arg == "--near"          ? o.near_plane
                                    : o.background_threshold) = v;
    } else if (arg == "--far") {
        float v = 0;
        if (!parse_float(value, v, /*allow_inf*/ true) || !(v > 0.0f)) return where + "expected a positive number or inf";
        o.far_plane = v;
    } else if (arg == "--motion-scale") {
        std::size_t comma = value.find(',');
        float sx = 0, sy = 0;
        if (comma == std::string::npos || !parse_float(value.substr(0, comma), sx) || !parse_float(value.substr(comma + 1), sy))
            return where + "expected two numbers SX,SY (e.g. 1,-1)";
        if (sx == 0.0f || sy == 0.0f) return where + "the scales must be non-zero";
        o.motion_scale[0] = sx;
        o.motion_scale[1] = sy;
    } else if (arg == "--camera") {
        if (value.empty()) return "option --camera: the file name is empty";
        o.camera_file = value;
    } else if (arg == "--device") {
        if (value.empty()) return "option --device: the name is empty";
        o.device = value;
    } else if (arg == "--signal") {
        SignalOptions s;
        std::string err;
        if (!parse_signal_spec(value, s, err)) return err;
        for (const SignalOptions& prev : o.signals)
            if (prev.layer == s.layer) return "--signal " + quoted(value) + ": layer " + quoted(s.layer) + " given twice";
        if (o.signals.size() >= RRC_MAX_CHANNELS)
            return "--signal " + quoted(value) + ": at most " + std::to_string(RRC_MAX_CHANNELS) + " signals per run";
        o.signals.push_back(s);
    }
    return "";
}

bool is_value_option(const std::string& arg) {
    const std::vector<std::string>& valued = value_options();
    return std::find(valued.begin(), valued.end(), arg) != valued.end();
}

}  // namespace

ParseResult parse_arguments(int argc, const char* const* argv) {
    ParseResult r;
    Options& o = r.options;

    auto fail = [&](const std::string& msg) {
        r.error = msg;
        return r;
    };

    // The host programs' one cursor (options_parser.h): --name=value, "needs a value", "takes no value",
    // unknown options and "given more than once" read the same in every program.
    rrc_host::ArgCursor c(argc, argv);
    try {
        while (c.next()) {
            const std::string arg = c.arg();
            if (c.flag("--validation"))
                o.validation = true;
            else if (c.flag("--no-object-id"))
                o.no_object_id = true;
            else if (c.flag("--quiet"))
                o.quiet = true;
            else if (c.flag("--verbose"))
                o.verbose = true;
            else if (!is_value_option(arg))
                c.unknown();
            else {
                const std::string error = parse_value_option(c, o);
                if (!error.empty()) return fail(error);
            }
        }
    } catch (const rrc_host::OptionError& e) {
        return fail(e.what());
    }
    o.check_options = c.check_only();
    o.help = c.help();

    if (o.help) return r;
    if (o.no_object_id && !o.object_id_channel.empty()) return fail("options --object-id and --no-object-id contradict each other");
    // rrc.h: ADAPTIVE with a non-zero epsilon_scale, epsilon or tau is
    // refused by the library; say which option it was before any file is read.
    if (o.depth_test == RRC_DEPTH_TEST_ADAPTIVE) {
        for (const char* tolerance : {"--epsilon", "--epsilon-scale", "--tau"})
            if (c.given(tolerance))
                return fail(std::string("option --depth-test adaptive sets its own tolerance: it cannot be combined with ") + tolerance +
                            " (use --depth-test fixed)");
        if (o.preset == "blender")
            return fail(
                "option --depth-test adaptive cannot be combined with --preset blender, which sets --tau: on linear depth with plain "
                "motion vectors both tests are tau x depth, so adaptive would only drop the preset's tau (docs/measurements/OFFLINE.md)");
    }
    if (o.preset == "blender") {
        // What Blender 3.x writes (docs/measurements/OFFLINE.md); anything given explicitly wins.
        // The library's RRC_PRESET_OFFLINE context: its motion_scale {1/W, -1/H} says pixels (not 1) and y up (negative).
        const rrc_context_desc p = blender_preset_context(2, 2);
        if (!c.given("--depth-mode")) o.depth_mode = p.depth_mode;
        if (!c.given("--reproject") && p.reprojection == RRC_REPROJECTION_MOTION) o.reproject = Reproject::Motion;
        if (!c.given("--motion-units") && p.motion_scale[0] != 1.0f) o.motion_units = MotionUnits::Pixels;
        if (!c.given("--motion-y")) o.motion_y_up = p.motion_scale[1] < 0.0f;
        if (!c.given("--tau")) o.tau = p.tau;
    } else if (!o.view_layer.empty()) {
        return fail("option --view-layer needs --preset blender");
    }
    if (o.input_pattern.empty()) return fail("missing required option --input PATTERN (see --help)");
    if (o.output_pattern.empty()) return fail("missing required option --output PATTERN (see --help)");
    if (!c.given("--frames")) return fail("missing required option --frames A-B (see --help)");
    if (o.reproject == Reproject::Camera && o.camera_file.empty())
        return fail("option --reproject camera needs --camera FILE (the view-projection matrices)");
    if (o.near_plane > 0.0f && o.far_plane > 0.0f && !(o.far_plane > o.near_plane)) return fail("option --far must be greater than --near");
    if (o.input_pattern == o.output_pattern)
        return fail("option --output: the output pattern equals the input pattern; inputs are never overwritten");
    if (!o.coherence_pattern.empty() && o.coherence_pattern == o.output_pattern)
        return fail("option --coherence: the PNG pattern equals the --output pattern");
    if (!o.metrics_file.empty() && o.reference_pattern.empty())
        return fail("option --metrics needs --reference PATTERN (the frames to measure against)");
    if (!o.reference_pattern.empty() && o.reference_pattern == o.input_pattern)
        return fail("option --reference: the reference pattern equals the input pattern");
    if (c.given("--from") && o.clean_report.empty()) return fail("option --from needs --clean-report FILE");
    // A range that ends before the default first frame is summarised whole.
    if (!c.given("--from") && o.clean_from > o.last_frame) o.clean_from = o.first_frame;
    if (!o.clean_report.empty() && o.clean_from > o.last_frame)
        return fail("option --from " + std::to_string(o.clean_from) + ": after the last frame (" + std::to_string(o.last_frame) +
                    "); the --clean-report summary would be empty");
    return r;
}

}  // namespace rrc_cli
