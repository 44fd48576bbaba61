// rrc-accumulate: command-line options.  parse_arguments() only parses and
// checks what can be checked without reading a file; it never prints and
// never exits, so tests call it directly.
#ifndef RRC_ACCUMULATE_OPTIONS_H
#define RRC_ACCUMULATE_OPTIONS_H

#include <rrc/rrc.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rrc_cli {

enum class Reproject { PrevClip, Motion, Camera };
enum class MotionUnits { Uv, Pixels };    /* --motion-units: uv (of the image) or pixels */
enum class Progress { Auto, Bar, Lines }; /* --progress; auto: a bar on a terminal, lines otherwise */

/** --preset blender's accumulation of <view layer>.Combined when no --signal is
 *  given: the library's RRC_PRESET_OFFLINE channel at this tool's tuning
 *  (docs/reference/presets.md; chosen in docs/measurements/OFFLINE.md, section 7).  An
 *  explicit --signal takes the tool's defaults and its own keys.  Throws
 *  std::runtime_error if the library refuses. */
rrc_channel_desc blender_preset_channel();
/** The context members the preset fixes (RRC_PRESET_OFFLINE: LINEAR depth, plain
 *  motion vectors in pixels with y up, tau) for a width x height sequence. */
rrc_context_desc blender_preset_context(uint32_t width, uint32_t height);
/** The preset's relative depth tolerance (tau for LINEAR depth with plain motion vectors). */
float blender_preset_tau();

/** One --signal NAME[:key=value,...]; the defaults are the paper's filter. */
struct SignalOptions {
    std::string layer;                                       /* EXR layer name: "shadow", "color" */
    float lambda = 0.6f;                                     /* lambda=  (3/5, the paper's) */
    rrc_blend blend = RRC_BLEND_FIXED;                       /* blend=fixed|age_aware|running_mean */
    rrc_history_filter filter = RRC_HISTORY_FILTER_BILINEAR; /* filter=nearest|bilinear|catmull_rom */
    rrc_history_precision history = RRC_HISTORY_FP16;        /* history=fp16|fp32 */
    uint32_t max_age = 255;                                  /* max_age=1..65535 */
    /* The spatial fill for young pixels (docs/CONVENTIONS.md, "The spatial fill"); 0 = off / the library's default. */
    uint32_t fill_age = 0;              /* fill=1..max_age+1 */
    uint32_t fill_radius = 0;           /* fill_radius=1..RRC_MAX_FILL_RADIUS, needs fill */
    float fill_depth_tolerance = 0.0f;  /* fill_tolerance=(0, 1], needs fill */
    /* The cures for error under motion (docs/CONVENTIONS.md, "Rectification", "The lag detector",
     * "The blur bound"); 0 = off / the library's default. */
    uint32_t rectify = 0;               /* rectify=on|off */
    float rectify_gamma = 0.0f;         /* rectify_gamma=(0, RRC_MAX_RECTIFY_GAMMA], needs rectify */
    uint32_t antilag = 0;               /* antilag=on|off */
    float antilag_gamma = 0.0f;         /* antilag_gamma=(0, RRC_MAX_ANTILAG_GAMMA], needs antilag */
    float antilag_threshold = 0.0f;     /* antilag_threshold=(0, RRC_MAX_ANTILAG_THRESHOLD], needs antilag */
    float blur_bound = 0.0f;            /* blur_bound=(0, RRC_MAX_BLUR_BOUND] px^2 */
    float gate_kappa = 0.0f;            /* gate=(0, RRC_MAX_GATE_KAPPA]: the deviation gate's kappa */
};

struct Options {
    bool help = false;
    bool check_options = false; /* --check-options: parse and check, print "options ok", read no file */

    std::string input_pattern;  /* --input, printf-style: frames/f_%04d.exr */
    std::string output_pattern; /* --output */
    int64_t first_frame = 0;    /* --frames A-B (or A) */
    int64_t last_frame = -1;

    rrc_depth_mode depth_mode = RRC_DEPTH_MODE_STANDARD;      /* --depth-mode */
    rrc_depth_format depth_format = RRC_DEPTH_FORMAT_FLOAT32; /* --depth-format */
    float epsilon = 0.0f;                                     /* --epsilon: absolute; 0 = from the format */
    float epsilon_scale = 0.0f;                               /* --epsilon-scale; 0 = library default */
    float tau = 0.0f;                                         /* --tau; 0 = library default 0.01 */
    float background_threshold = 0.0f;                        /* --background-threshold; 0 = library default */
    rrc_depth_test depth_test = RRC_DEPTH_TEST_DEFAULT;       /* --depth-test default|adaptive|fixed (rrc.h) */
    float near_plane = 0.0f;                                  /* --near */
    float far_plane = 0.0f;                                   /* --far (may be inf) */

    Reproject reproject = Reproject::PrevClip;  /* --reproject */
    float motion_scale[2] = {1.0f, 1.0f};       /* --motion-scale sx,sy (after the units and y sign) */
    MotionUnits motion_units = MotionUnits::Uv; /* --motion-units uv|pixels */
    bool motion_y_up = false;                   /* --motion-y up|down */
    std::string camera_file;                    /* --camera */
    std::vector<int64_t> cuts;                  /* --cut F[,F...]: camera cuts, every pixel misses */

    /* --preset blender: Blender 3.x multilayer EXR passes.  Applied by
     * parse_arguments to every option not given: --depth-mode linear,
     * --reproject motion, --motion-units pixels, --motion-y up, --tau
     * blender_preset_tau(); the channel names (<view layer>.Depth.Z,
     * <view layer>.Vector.X/Y, signal <view layer>.Combined, object ids
     * <view layer>.IndexOB.X if present) are resolved from the first frame
     * by discover_layout, which gives the signal blender_preset_signal()'s
     * settings when no --signal is given. */
    std::string preset;
    std::string view_layer; /* --view-layer: Blender's view layer name (the preset finds it otherwise) */

    /* Channel names; empty = the default (or the preset's). */
    std::string depth_channel;                  /* --depth-channel (Z) */
    std::vector<std::string> motion_channels;   /* --motion-channels X,Y[,Z] (mv.X,mv.Y[,mv.Z]) */
    std::vector<std::string> prevclip_channels; /* --prevclip-channels X,Y,Z,W (prevclip.X,...) */
    std::string nocache_channel;                /* --nocache-channel (nocache.Y) */
    /* --object-id: the per-pixel object id channel (none by default;
     * --preset blender: <view layer>.IndexOB.X when the first frame has it).
     * With ids a hit also needs every previous depth tap of non-zero weight
     * on the pixel's object (rrc_context_desc.use_object_id). */
    std::string object_id_channel;
    bool no_object_id = false; /* --no-object-id: never read object ids (the preset's included) */

    std::vector<SignalOptions> signals; /* --signal, repeatable; empty: every layer */

    std::string coherence_pattern; /* --coherence: PNG hit/miss maps, printf-style */
    std::string reference_pattern; /* --reference: converged frames to measure against */
    std::string metrics_file;      /* --metrics: CSV path; default <output directory>/metrics.csv */
    float psnr_peak = 1.0f;        /* --psnr-peak: PSNR = 10 log10(peak^2 / MSE) */
    /* --clean-report FILE.md|FILE.csv: the output against each frame's own input, by region
     * (clean_regions.h; docs/measurements/OFFLINE.md, "What rrc adds to a clean input"). */
    std::string clean_report;
    int64_t clean_from = 8; /* --from N: the report's summary is over frames >= N (the error study's) */

    std::string device;                 /* --device */
    bool validation = false;            /* --validation */
    bool quiet = false;                 /* --quiet */
    bool verbose = false;               /* --verbose */
    Progress progress = Progress::Auto; /* --progress auto|bar|lines */
};

struct ParseResult {
    Options options;
    std::string error; /* empty on success; otherwise names the offending option */
    bool ok() const { return error.empty(); }
};

/** argv[0] is the program name and is skipped.  Options take their value as
 *  the next argument or after '=' (--epsilon=1e-6).  With --help nothing is
 *  required. */
ParseResult parse_arguments(int argc, const char* const* argv);

/** Every option that takes a value (--name VALUE or --name=VALUE), as the parser knows them. */
const std::vector<std::string>& value_options();

/** The --help text: every option, the channel names, the exit codes. */
std::string usage_text();

/** The signal --preset blender accumulates when no --signal is given: `layer`
 *  (<view layer>.Combined) with blender_preset_channel()'s lambda, blend,
 *  filter, fill age and rectification, the other keys the tool's defaults. */
SignalOptions blender_preset_signal(const std::string& layer);

/** "NAME[:key=value,...]"; on failure returns false and sets error. */
bool parse_signal_spec(const std::string& text, SignalOptions& out, std::string& error);

/** "A-B" or "A", 0 <= A <= B. */
bool parse_frame_range(const std::string& text, int64_t& first, int64_t& last, std::string& error);

/** A pattern holds exactly one integer conversion (%d, %i, %u with an
 *  optional 0 flag and width, e.g. %04d) and any number of "%%". */
bool validate_pattern(const std::string& pattern, std::string& error);

/** The pattern with the frame number substituted; the pattern must be valid. */
std::string format_frame_path(const std::string& pattern, int64_t frame);

/** The CSV path --reference writes: --metrics, or metrics.csv in the
 *  directory of the output pattern. */
std::string metrics_path(const Options& options);

/** Names used in messages and output: "prev_clip", "standard", "fp16"... */
const char* reproject_name(Reproject r);
const char* depth_mode_name(rrc_depth_mode m);
const char* depth_test_name(rrc_depth_test t);

}  // namespace rrc_cli

#endif
