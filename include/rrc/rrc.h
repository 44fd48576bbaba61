/*
 * rrc — the real-time reprojection cache (Nehab, Sander et al. 2007) as a
 * drop-in temporal-accumulation library.  Core C99 API, no Vulkan types.
 *
 * Reference manual
 * ================
 * Each frame the host hands the library its depth, its reprojection data
 * (previous clip positions, motion vectors, or just camera matrices) and one
 * to RRC_MAX_CHANNELS noisy per-frame signals ("channels").  One fused
 * compute kernel reverse-reprojects every pixel into the previous frame,
 * decides hit or miss with the epsilon-depth test against the previous depth
 * buffer (hand-written bilinear fetch) and updates each channel's history
 * with the lambda recursive filter while tracking the per-pixel age.  The
 * exact conventions (coordinates, depth modes, jitter, fetch, hit test,
 * filter) are in docs/CONVENTIONS.md; every choice this header leaves to the
 * library is written down there.
 *
 * Every member and function by concept: docs/reference/api.md, "The API by concept".
 *
 * Lifetime
 * --------
 *   rrc_validate_context_desc()  check a descriptor; no Vulkan object made
 *   rrc_context_create()         make a context (and, standalone, a device)
 *   rrc_frame_run()              per frame: CPU arrays in, CPU arrays out
 *   rrc_frame_classify() and     per frame, shading cache: which quads the
 *   rrc_frame_resolve()          host must shade, then its values merged in
 *   rrc_context_destroy()        free everything
 *
 * Errors
 * ------
 * Every entry point validates its arguments and returns an rrc_result.  On
 * any error nothing is written to the caller's outputs and the context is
 * left as it was.  A readable message naming the offending field is kept:
 * rrc_context_last_error() for calls on a context, rrc_last_error() (per
 * thread) for every call, and the log callback receives it too.  Nothing
 * throws across this API.
 *
 * Thread safety
 * -------------
 * A context is externally synchronised: never call into one context from two
 * threads at once.  A call that finds another in progress on its context (a
 * second thread, or a call from inside the first one's log callback) is
 * refused with RRC_ERROR_UNSUPPORTED and touches nothing of the context
 * (0.10; a cheap check, not a lock: it sees overlapping calls, not every
 * misuse).  Distinct contexts are independent and may be driven from
 * different threads concurrently.  rrc_validate_context_desc(),
 * rrc_get_version() and rrc_result_to_string() are thread-safe.
 *
 * Versioning
 * ----------
 * RRC_API_VERSION encodes major.minor.patch.  Callers put the version they
 * compiled against in rrc_context_desc.api_version; create refuses another
 * major version (RRC_ERROR_INCOMPATIBLE_VERSION).  Within a major version the
 * API only grows, and a caller built against an older minor version keeps
 * working unchanged with a newer library.  The rules that make this true:
 *
 *  1. Every struct the caller fills starts with an rrc_struct_header: a type
 *     tag, a `next` pointer and `size` = sizeof(the struct as the caller
 *     compiled it).  A size below the struct's first published size (its 0.1
 *     size) is RRC_ERROR_INVALID_STRUCT.
 *  2. New members are only ever appended.  The library reads a struct up to
 *     the caller's `size`; members beyond it read as zero, and a zeroed
 *     member always means the old behaviour.  A struct larger than the
 *     library knows (a newer header's) is accepted when every byte beyond
 *     what the library knows is zero, and refused with RRC_ERROR_UNSUPPORTED
 *     otherwise (the caller asked for something this library cannot do).
 *     A `size` above RRC_MAX_STRUCT_SIZE is RRC_ERROR_INVALID_STRUCT, refused
 *     before any byte past the struct the library knows is read (0.10).
 *  3. Arrays of tagged structs (desc.channels, frame.channels,
 *     output.channels, and rrc_frame_run_batch's frames and outputs) are
 *     strided by their elements' `size`: element i
 *     starts at (const char*)array + i * array[0].size, and every element
 *     must carry the same size (else RRC_ERROR_INVALID_STRUCT).
 *  4. Output structs are written only up to the caller's `size`.
 *  5. `next` is NULL or a chain of extension structs, each starting with an
 *     rrc_struct_header whose type is an RRC_STRUCT_TYPE_EXT_* tag (tags
 *     0x525243E0..0x525243FF are reserved for extensions).  The library walks
 *     the chain, finds the extensions the parent struct documents by type, and
 *     validates each by rule 1-2.  An extension type this library does not
 *     know is RRC_ERROR_UNSUPPORTED; a base struct's tag in a chain, a type
 *     twice, an extension on a parent that does not take it, or a chain
 *     longer than RRC_MAX_CHAIN (a cycle) is RRC_ERROR_INVALID_STRUCT.
 *     Version 0.11 defines the first: rrc_vulkan_image_extents (rrc_vulkan.h).
 *  6. Existing exported functions keep their signatures; a better name is
 *     added beside an old one, which stays exported as an alias until 1.0.
 *
 * docs/guide/integration.md lists the changes of each minor version.
 *
 * Conventions of this header: one prefix (rrc_, RRC_), fixed-width fields,
 * enums stored as uint32_t, no bool, no unions, zero means default.
 */
#ifndef RRC_RRC_H
#define RRC_RRC_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32)
#    if defined(RRC_BUILDING_LIBRARY)
#        define RRC_API __declspec(dllexport)
#    else
#        define RRC_API __declspec(dllimport)
#    endif
#elif defined(__GNUC__)
#    define RRC_API __attribute__((visibility("default")))
#else
#    define RRC_API
#endif

/* ---- Version ----------------------------------------------------------- */

#define RRC_MAKE_VERSION(major, minor, patch) ((((uint32_t)(major)) << 22) | (((uint32_t)(minor)) << 12) | ((uint32_t)(patch)))
#define RRC_VERSION_MAJOR(v) ((uint32_t)(v) >> 22)
#define RRC_VERSION_MINOR(v) (((uint32_t)(v) >> 12) & 0x3FFu)
#define RRC_VERSION_PATCH(v) ((uint32_t)(v)&0xFFFu)

/** The version of this header. */
#define RRC_API_VERSION RRC_MAKE_VERSION(0, 13, 0)

/** The largest `size` a tagged struct may state (Versioning, rule 2): far
 *  above any struct of this API, so that a garbage size is refused before
 *  the library reads past the caller's struct (0.10). */
#define RRC_MAX_STRUCT_SIZE 4096u

/** The version of the library actually loaded. */
RRC_API uint32_t rrc_get_version(void);

/* Enumerated values.  Every value of the enumerations below (and the limits
 * RRC_MAX_CHANNELS, RRC_MAX_NAME, RRC_MAX_AGE_CAP, RRC_MAX_EXTENT) is
 * written once, with its comment, in an X-macro list RRC_<TYPE>_VALUES(X) of
 * <rrc/rrc_values.h>, which the library's GLSL kernels include too.  Here
 * each list becomes
 *     typedef enum rrc_<type>_enum { ..., RRC_<TYPE>_MAX_ENUM = 0x7FFFFFFF } rrc_<type>_enum;
 * (the naming of every enum type of this header), so debuggers show names.
 * Struct members, parameters and the rrc_<type> typedefs stay uint32_t
 * (rrc_result: int32_t): the enums never set a size or layout.  In C++11
 * and later each enum has that fixed underlying type, so its values compare
 * and combine with the members exactly as unsigned (signed for results)
 * integers; in C they are int constants. */
#include "rrc_values.h"
#if defined(__cplusplus) && (__cplusplus >= 201103L || (defined(_MSVC_LANG) && _MSVC_LANG >= 201103L))
#    define RRC_ENUM_BASE(type) : type
#else
#    define RRC_ENUM_BASE(type)
#endif
#define RRC_ENUM_VALUE(name, value) name = value,
/* RRC_DEFINE_ENUM(rrc_blend, RRC_BLEND, uint32_t) declares
 *     typedef uint32_t rrc_blend;
 *     typedef enum rrc_blend_enum { RRC_BLEND_VALUES..., RRC_BLEND_MAX_ENUM = 0x7FFFFFFF } rrc_blend_enum; */
#define RRC_DEFINE_ENUM(type, PREFIX, base) \
    typedef base type;                      \
    typedef enum type##_enum RRC_ENUM_BASE(base){PREFIX##_VALUES(RRC_ENUM_VALUE) PREFIX##_MAX_ENUM = 0x7FFFFFFF} type##_enum;

/* ---- Results ------------------------------------------------------------ */

RRC_DEFINE_ENUM(rrc_result, RRC_RESULT, int32_t)

/** A static, never-NULL name for a result code ("RRC_ERROR_SIZE_MISMATCH"). */
RRC_API const char* rrc_result_to_string(rrc_result result);

/** The message of the last failed call on this thread ("" if none).  Valid
 *  until the next rrc_ call on this thread. */
RRC_API const char* rrc_last_error(void);

/* ---- Struct tags ------------------------------------------------------- */

typedef uint32_t rrc_struct_type;
#define RRC_STRUCT_TYPE_CONTEXT_DESC 0x52524301u
#define RRC_STRUCT_TYPE_CHANNEL_DESC 0x52524302u
#define RRC_STRUCT_TYPE_FRAME_DESC 0x52524303u
#define RRC_STRUCT_TYPE_CHANNEL_INPUT 0x52524304u
#define RRC_STRUCT_TYPE_FRAME_OUTPUT 0x52524305u
#define RRC_STRUCT_TYPE_CHANNEL_OUTPUT 0x52524306u
#define RRC_STRUCT_TYPE_CLASSIFY_OUTPUT 0x52524307u /* 0.3 */
#define RRC_STRUCT_TYPE_RESOLVE_DESC 0x52524308u    /* 0.3 */

/** The first members of every tagged struct, and of every extension struct
 *  on a `next` chain (Versioning, rules 1-5). */
typedef struct rrc_struct_header {
    rrc_struct_type type;
    const void* next;
    uint32_t size;
} rrc_struct_header;

/** Longest `next` chain the library walks before calling it a cycle. */
#define RRC_MAX_CHAIN 64

/* ---- Enumerations (stored as uint32_t; 0 is the default) --------------- */

/** How the depth the host passes is encoded (docs/CONVENTIONS.md §depth). */
RRC_DEFINE_ENUM(rrc_depth_mode, RRC_DEPTH_MODE, uint32_t)

/** The host's depth-buffer format: sets epsilon, "the smallest z increment". */
RRC_DEFINE_ENUM(rrc_depth_format, RRC_DEPTH_FORMAT, uint32_t)

/** Where the previous-frame position of each pixel comes from. */
RRC_DEFINE_ENUM(rrc_reprojection, RRC_REPROJECTION, uint32_t)

/** Which depth test decides a hit (docs/CONVENTIONS.md §hit test). */
RRC_DEFINE_ENUM(rrc_depth_test, RRC_DEPTH_TEST, uint32_t)

/** The lambda recursive filter's blend (docs/CONVENTIONS.md §filter). */
RRC_DEFINE_ENUM(rrc_blend, RRC_BLEND, uint32_t)

/** Which hits a REUSE channel re-shades anyway (docs/CONVENTIONS.md §refresh). */
RRC_DEFINE_ENUM(rrc_refresh_policy, RRC_REFRESH_POLICY, uint32_t)

/** How history is resampled at the reprojected position. */
RRC_DEFINE_ENUM(rrc_history_filter, RRC_HISTORY_FILTER, uint32_t)

RRC_DEFINE_ENUM(rrc_history_precision, RRC_HISTORY_PRECISION, uint32_t)
/** fp16 history is kept only while the largest effective lambda a channel can
 *  reach (FIXED: lambda; AGE_AWARE: min(lambda, cap/(cap+1)); RUNNING_MEAN:
 *  cap/(cap+1)) is at most this; above it the channel's history is fp32.
 *  Why: a history rounded to nearest fp16 stops moving once
 *  (1 - lambda)|s - H| < ulp(H)/2, i.e. it may stall up to 2^-11/(1 - lambda)
 *  of H away from the signal (bias 3.6e-2 at lambda 0.999 on a noisy signal;
 *  docs/measurements/STABILITY.md).  REUSE never blends: it keeps fp16. */
#define RRC_FP16_MAX_LAMBDA 0.95

/** Bits of the per-pixel mask (rrc_frame_output.mask is uint8_t). */
typedef enum rrc_mask_enum RRC_ENUM_BASE(uint32_t){RRC_MASK_VALUES(RRC_ENUM_VALUE) RRC_MASK_MAX_ENUM = 0x7FFFFFFF} rrc_mask_enum;

/* The limits RRC_MAX_CHANNELS, RRC_MAX_NAME, RRC_MAX_AGE_CAP and
 * RRC_MAX_EXTENT are in <rrc/rrc_values.h> (the kernels need them too). */

/** The defaults a zeroed member stands for (docs/CONVENTIONS.md). */
#define RRC_DEFAULT_AGE_CAP 255u               /* rrc_channel_desc.age_cap */
#define RRC_DEFAULT_BACKGROUND_THRESHOLD 1e10f /* rrc_context_desc.background_threshold */
#define RRC_DEFAULT_EPSILON_SCALE_FLOAT32 4.0f /* rrc_context_desc.epsilon_scale, FLOAT32 */
#define RRC_DEFAULT_EPSILON_SCALE_UNORM 1.0f   /* rrc_context_desc.epsilon_scale, UNORM16/24 */
#define RRC_DEFAULT_TAU 0.01f                  /* rrc_context_desc.tau */
#define RRC_DEFAULT_RECTIFY_GAMMA 1.0f         /* rrc_channel_desc.rectify_gamma (0.4) */
#define RRC_MAX_RECTIFY_GAMMA 16.0f
#define RRC_DEFAULT_BLUR_SIGMA 0.5f            /* rrc_channel_desc.blur_sigma (0.4) */
#define RRC_MAX_BLUR_SIGMA 0.8164966f          /* sqrt(2/3): the blur's 3 taps stay decreasing */
#define RRC_DEFAULT_FILL_RADIUS 2u             /* rrc_channel_desc.fill_radius (0.4) */
#define RRC_MAX_FILL_RADIUS 4u
#define RRC_DEFAULT_ANTILAG_GAMMA 2.0f        /* rrc_channel_desc.antilag_gamma (0.5) */
#define RRC_MAX_ANTILAG_GAMMA 16.0f
#define RRC_DEFAULT_ANTILAG_THRESHOLD 0.5f    /* rrc_channel_desc.antilag_threshold (0.5) */
#define RRC_MAX_ANTILAG_THRESHOLD 2.0f        /* the relative gap is below 2 */
#define RRC_MAX_BLUR_BOUND 64.0f              /* rrc_channel_desc.blur_bound (0.6), px^2: a blur of 8 px standard deviation */
#define RRC_MAX_VIEW_LOBE 3.14159265f         /* rrc_channel_desc.view_lobe (0.7), radians: pi */
#define RRC_MAX_GATE_KAPPA 16.0f              /* rrc_channel_desc.gate_kappa (0.12), standard errors */
#define RRC_DEFAULT_FILL_DEPTH_TOLERANCE 0.005f /* rrc_channel_desc.fill_depth_tolerance (0.4; docs/measurements/PERFORMANCE.md "The spatial fill (soft shadows)") */

/* ---- Logging ----------------------------------------------------------- */

RRC_DEFINE_ENUM(rrc_log_level, RRC_LOG_LEVEL, uint32_t)

/** Receives UTF-8, NUL-terminated text valid only during the call. */
typedef void (*rrc_log_fn)(void* user, rrc_log_level level, const char* message);

/* ---- Context description ----------------------------------------------- */

/** One accumulated signal. */
typedef struct rrc_channel_desc {
    rrc_struct_type type;            /* RRC_STRUCT_TYPE_CHANNEL_DESC */
    const void* next;                /* NULL or an extension chain (Versioning, rule 5) */
    uint32_t size;                   /* sizeof(rrc_channel_desc) */
    char name[RRC_MAX_NAME];         /* non-empty, unique in the context, NUL-terminated */
    uint32_t components;             /* 1 or 4 */
    rrc_history_precision precision; /* fp16 (default) or fp32; fp16 above RRC_FP16_MAX_LAMBDA is fp32 */
    float lambda;                    /* in [0,1); the weight of history. 0 with blend FIXED is no accumulation;
                                        REUSE ignores it */
    rrc_blend blend;
    rrc_history_filter filter;
    uint32_t age_cap;    /* saturation of the age count; 0 = default 255, at most RRC_MAX_AGE_CAP */
    uint32_t confidence; /* non-zero: the host passes a per-sample weight w in [0,1] */
    /* ---- 0.4: finishing steps (docs/CONVENTIONS.md, "Rectification",
     *      "The Gaussian history filter", "The spatial fill") ---- */
    /* Non-zero: history rectification.  On a blend (a hit with a valid
     * sample and a non-empty history) the resampled history is first clamped,
     * per component, to mu +- gamma * sigma of this frame's valid samples in
     * the pixel's 3x3 neighbourhood.  Accumulating blends only (REUSE refuses it). */
    uint32_t rectify;
    float rectify_gamma; /* gamma, in (0, RRC_MAX_RECTIFY_GAMMA]; 0 = default RRC_DEFAULT_RECTIFY_GAMMA */
    /* RRC_HISTORY_FILTER_GAUSSIAN: the standard deviation of the blur, in
     * pixels, in (0, RRC_MAX_BLUR_SIGMA]; 0 = default RRC_DEFAULT_BLUR_SIGMA.
     * Must be 0 with any other filter. */
    float blur_sigma;
    /* The spatial fill for young pixels (a second dispatch): non-zero = T,
     * pixels whose age after the frame is below T are shown as a depth-aware
     * mean over their cached neighbours (and the host's fallback); at most
     * the age cap + 1.  The fill is display-only: history keeps the channel's
     * own samples.  0 = off. */
    uint32_t fill_age;
    uint32_t fill_radius;       /* the window's half width r (a (2r+1)^2 window), 1..RRC_MAX_FILL_RADIUS; 0 = default */
    float fill_depth_tolerance; /* a neighbour counts when its depth is within this relative distance; 0 = default */
    /* The weight, in samples, of the host's fallback estimate
     * (rrc_channel_input.fallback, rrc_vulkan_channel_images.fallback), which
     * the frame must then carry; 0 = no fallback.  Needs fill_age. */
    float fill_prior;
    /* ---- 0.5: the lag detector (docs/CONVENTIONS.md, "The lag detector") ---- */
    /* Non-zero: anti-lag.  On a blend, the gap between the resampled history
     * and the box mu +- antilag_gamma * sigma of this frame's valid samples
     * in the 3x3 neighbourhood, relative to the signal's size, shortens the
     * history's age (and so the effective lambda) where the signal changed.
     * Accumulating blends only (REUSE refuses it). */
    uint32_t antilag;
    float antilag_gamma;     /* the box's half width in sigmas, in (0, RRC_MAX_ANTILAG_GAMMA]; 0 = default */
    float antilag_threshold; /* the relative gap at which the history is dropped, in (0, RRC_MAX_ANTILAG_THRESHOLD]; 0 = default */
    /* ---- 0.6: the blur bound (docs/CONVENTIONS.md, "The blur bound") ---- */
    /* B > 0: the resampling blur a stationary history may accumulate, in
     * px^2 per axis, in [0, RRC_MAX_BLUR_BOUND]; 0 = off.  On a blend, the
     * history's age is capped at floor(B / b), b the second moment of this
     * fetch's resampling weights (BILINEAR: f(1 - f); GAUSSIAN: plus
     * blur_sigma^2; NEAREST and CATMULL_ROM: 0, never capped), so that the
     * recursive filter's stationary blur lambda_eff/(1 - lambda_eff) * b
     * stays within B (Yang et al. 2009).  Accumulating blends only (REUSE
     * refuses it). */
    float blur_bound;
    /* ---- 0.7: the view-dependent history (docs/CONVENTIONS.md, "The
     *      view-dependent history") ---- */
    /* alpha > 0: the signal depends on the view direction (a reflection, a
     * specular lobe) with an angular width of alpha radians, in [0,
     * RRC_MAX_VIEW_LOBE]; 0 = off.  On a blend, with theta the angle by which
     * the view direction to the pixel's surface point turned since the frame
     * reprojected from, the history's age is capped at floor(alpha / theta),
     * so that its samples' mean offset in view direction stays within alpha
     * (in the manner of NRD's parallax-limited specular accumulation).  Every
     * frame then carries view_proj and both camera positions
     * (rrc_frame_desc, 0.7), whatever the reprojection source.
     * Accumulating blends only (REUSE refuses it). */
    float view_lobe;
    /* ---- 0.9: the residual (docs/CONVENTIONS.md, "The residual") ---- */
    /* Non-zero: the channel accumulates the sample less a base estimate b
     * the host supplies every frame (rrc_channel_input.fallback,
     * rrc_vulkan_channel_images.fallback, then required), and shows the
     * accumulated residual plus this frame's b.  b should be deterministic
     * (the same inputs give the same b: a noise-free, possibly biased
     * estimate such as PCSS for a soft shadow): the filter is linear, so the
     * variance is the sample's own, and the history lags only behind what b
     * did not follow.  With a fill_prior, b is the fill's prior (a residual
     * of 0).  Accumulating blends only (REUSE refuses it). */
    uint32_t residual;
    /* ---- 0.12: the deviation gate (docs/CONVENTIONS.md, "The deviation gate") ---- */
    /* kappa > 0: the channel keeps, per pixel, the running mean and mean
     * square of the deviation d = sample - history; on a blend, where the
     * mean (the history's bias) is large against the deviations' standard
     * error, the history's age is cut to the one at which the bias equals
     * kappa standard errors, so a history the resampling blurred away from a
     * clean signal is shortened while one that only carries noise is not.
     * In [0, RRC_MAX_GATE_KAPPA]; 0 = off.  Needs confidence = 0;
     * accumulating blends only (REUSE refuses it). */
    float gate_kappa;
} rrc_channel_desc;

typedef struct rrc_context_desc {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_CONTEXT_DESC */
    const void* next;     /* NULL or an extension chain (Versioning, rule 5) */
    uint32_t size;        /* sizeof(rrc_context_desc) */
    uint32_t api_version; /* RRC_API_VERSION the caller compiled against */

    uint32_t width, height; /* 1..RRC_MAX_EXTENT */

    rrc_depth_mode depth_mode;
    float near_plane;           /* view distance of the near plane; needed by MOTION with NDC depth */
    float far_plane;            /* may be +inf (REVERSED); needed by MOTION with NDC depth */
    float background_threshold; /* LINEAR: d >= this is background; 0 = default 1e10 */

    rrc_depth_format depth_format; /* NDC modes: which z increment makes epsilon */
    float epsilon_scale;           /* epsilon = scale * increment; 0 = default (1 unorm, 4 float32) */
    float epsilon;                 /* > 0: absolute epsilon (NDC modes), overrides format and scale */
    float tau;                     /* relative tolerance |diff| <= tau*d for LINEAR and linearised
                             MOTION tests; 0 = default 0.01 */

    rrc_reprojection reprojection;
    float motion_scale[2]; /* multiplies motion vectors into uv units; {0,0} = {1,1}.
                              Pixel vectors: {1/W, 1/H}; y-up: negate the second. */

    uint32_t channel_count; /* 1..RRC_MAX_CHANNELS */
    const rrc_channel_desc* channels;

    uint32_t use_nocache_mask; /* non-zero: frames carry a "do not cache" mask */

    /* Standalone device choice.  NULL and no RRC_DEVICE environment variable:
     * the first discrete GPU, else integrated, else any (lavapipe).
     * Otherwise the first device whose name contains this text. */
    const char* device_name;
    /* Non-zero (or RRC_VALIDATION=1 in the environment): enable the Khronos
     * validation layer with synchronization validation; every message goes to
     * the log at RRC_LOG_VALIDATION and is counted (rrc_context_validation_messages). */
    uint32_t enable_validation;

    rrc_log_fn log; /* optional */
    void* log_user; /* passed to log */

    /* ---- 0.2 (a 0.1 caller's size ends before this: read as zero) ---- */
    /* 0 = RRC_DEPTH_TEST_DEFAULT: ADAPTIVE when api_version >= 0.2 and none of
     * epsilon_scale, epsilon, tau is set; FIXED otherwise (a 0.1 caller keeps
     * the 0.1 test).  ADAPTIVE with a non-zero epsilon_scale, epsilon or tau
     * is RRC_ERROR_INVALID_ARGUMENT.  Every source with an exact expected
     * depth (PREV_CLIP, MOTION_DEPTH, CAMERA) adapts, in every depth mode;
     * plain MOTION's relative test is the same under both. */
    rrc_depth_test depth_test;
    /* Non-zero: frames carry a per-pixel object id (rrc_frame_desc.object_id,
     * rrc_vulkan_frame_desc.object_id), and a hit also needs every previous
     * depth tap with non-zero bilinear weight to carry the pixel's id. */
    uint32_t use_object_id;

    /* ---- 0.3: the shading cache (docs/CONVENTIONS.md §refresh) ---- */
    /* Which hits of REUSE channels are re-shaded anyway (a REFRESHED pixel is
     * not a HIT).  Needs at least one REUSE channel; accumulating channels
     * ignore it (they take a sample every frame).  NONE (0): none. */
    rrc_refresh_policy refresh_policy;
    /* n, the policy's period in frames: 1..RRC_MAX_REFRESH_PERIOD; every
     * pixel of a static scene is refreshed exactly once every n frames.
     * Required (non-zero) with a policy, 0 without. */
    uint32_t refresh_period;
    /* TILED: the grid {gx, gy}, gx * gy = refresh_period, each at most
     * RRC_MAX_REFRESH_TILES; {0, 0} = {refresh_period, 1} (vertical strips).
     * {0, 0} for the other policies. */
    uint32_t refresh_tiles[2];
    /* Non-zero: L, a REUSE value is re-shaded when it would be used for an
     * (L+1)-th frame, whatever the policy (bounds staleness under motion,
     * which screen-space policies cannot).  At most the age cap of every
     * REUSE channel.  Needs a REUSE channel. */
    uint32_t max_lifetime;
    /* Views: 0 = 1, at most RRC_MAX_VIEWS.  Each view keeps its own previous
     * depth, ids, histories and ages (memory grows with the count); a frame
     * names the view it writes and the view it reprojects from
     * (rrc_frame_desc.view, .reproject_from): a stereo eye from the other
     * eye, a motion-blur sub-frame or a lens sample from the one before. */
    uint32_t view_count;
} rrc_context_desc;

/** Check a context descriptor without touching Vulkan.  Returns RRC_SUCCESS or
 *  the code create would fail with; the message (naming the field) is
 *  available from rrc_last_error().  Cheap: fuzzers call it many times. */
RRC_API rrc_result rrc_validate_context_desc(const rrc_context_desc* desc);

/* ---- Presets (0.11): one application's settings, tuned and measured ----- *
 * A preset fills the members of a description that an application's best
 * measured setting decides; docs/guide/ has one guide per application: what
 * the host renders each frame, the inputs, each value and what it buys.
 *
 *   rrc_channel_desc ch = {RRC_STRUCT_TYPE_CHANNEL_DESC, NULL, sizeof ch, "shadow", 1};
 *   rrc_channel_preset(RRC_PRESET_PCF_SHADOWS, RRC_PRESET_FLAG_BASE, RRC_API_VERSION, &ch);
 *
 * flags: RRC_PRESET_FLAG_BASE, for PCF_SHADOWS, ENV_BUMP and SOFT_SHADOWS only: the
 * host renders the application's deterministic base every frame and passes it
 * as the channel's fallback image (the residual, docs/CONVENTIONS.md "The
 * residual"; the guide says what the base is).  Without it, the best measured
 * setting that needs no image but the sample.  Any other flag, or the flag
 * with another preset, is RRC_ERROR_INVALID_ARGUMENT.
 *
 * tuning: the RRC_API_VERSION whose values to take.  A later version that
 * re-tunes a preset adds its new values under its own version and keeps
 * every earlier tuning, so passing the RRC_API_VERSION you compiled (and
 * tested) against gives the same values from every later library.  0: the
 * loaded library's latest.  A version before 0.11 takes 0.11's (the first);
 * one newer than the loaded library is RRC_ERROR_UNSUPPORTED.
 *
 * What is written: the channel's size, tag and version rules apply (rule 1);
 * the preset writes lambda, blend, filter, age_cap and every member from
 * rectify on, each only where the caller's `size` holds it (rule 4),
 * including the ones it leaves off (as 0).  type, next, size, name,
 * components, precision and confidence stay the caller's.  On an error
 * nothing is written.  The result always passes validation. */
RRC_DEFINE_ENUM(rrc_preset, RRC_PRESET, uint32_t)
#define RRC_PRESET_FLAG_BASE 0x1u /* the host renders the base (the residual variant) */

RRC_API rrc_result rrc_channel_preset(rrc_preset preset, uint32_t flags, uint32_t tuning, rrc_channel_desc* channel);

/** The context members an application fixes, as rrc_channel_preset (flags
 *  and tuning alike).  OFFLINE (Cycles passes, docs/guide/offline.md): LINEAR
 *  depth, plain MOTION vectors in pixels with y up (motion_scale {1/W, -1/H}:
 *  set width and height first, else RRC_ERROR_INVALID_ARGUMENT), tau and the
 *  FIXED depth test tau needs.  SHADING_CACHE: refresh_policy, refresh_period,
 *  refresh_tiles and max_lifetime.  PCF_SHADOWS, ENV_BUMP and SOFT_SHADOWS fix
 *  no context member: nothing is written.  Members are written only within
 *  the caller's `size`; on an error nothing is written. */
RRC_API rrc_result rrc_context_preset(rrc_preset preset, uint32_t flags, uint32_t tuning, rrc_context_desc* context);

/* ---- Context ----------------------------------------------------------- */

typedef struct rrc_context rrc_context;

/** Validates desc, creates a standalone Vulkan device and every resource.
 *  *out_context is set only on success. */
RRC_API rrc_result rrc_context_create(const rrc_context_desc* desc, rrc_context** out_context);

/** Frees everything.  NULL is allowed and ignored. */
RRC_API void rrc_context_destroy(rrc_context* context);

/** The last error message of calls on this context ("" if none). */
RRC_API const char* rrc_context_last_error(const rrc_context* context);

/** The name of the Vulkan device the context runs on (NUL-terminated). */
RRC_API rrc_result rrc_context_device_name(const rrc_context* context, char* out_name, size_t capacity);

/** Device memory the context owns (history, ages, weights, previous depth,
 *  its own input copies and staging), in bytes.  (0.2; the 0.1 name
 *  rrc_get_memory_usage stays exported as an alias until 1.0.) */
RRC_API rrc_result rrc_context_memory_usage(const rrc_context* context, uint64_t* out_bytes);
/** Deprecated alias of rrc_context_memory_usage (0.1 name). */
RRC_API rrc_result rrc_get_memory_usage(const rrc_context* context, uint64_t* out_bytes);

/** Number of validation-layer messages seen so far (0 if validation is off).
 *  A context of rrc_vulkan_context_create cannot count them (the layer
 *  reports to the host's own instance): RRC_ERROR_UNSUPPORTED, nothing
 *  written (0.10; before, it reported 0). */
RRC_API rrc_result rrc_context_validation_messages(const rrc_context* context, uint64_t* out_count);

/* ---- Frames (standalone: CPU arrays) ----------------------------------- */

/** One channel's per-frame input.  Arrays are row-major, row 0 at the top. */
typedef struct rrc_channel_input {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_CHANNEL_INPUT */
    const void* next;
    uint32_t size;
    const float* samples;    /* width*height*components, interleaved; required */
    const float* confidence; /* width*height weights in [0,1]; required iff the channel has confidence */
    /* ---- 0.4 ---- */
    const float* fallback; /* width*height*components: the host's estimate for young pixels (soft shadows: PCSS),
                              and with residual (0.9) the base the residual is taken against;
                              required iff the channel's fill_prior > 0 or residual, else ignored */
} rrc_channel_input;

typedef struct rrc_frame_desc {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_FRAME_DESC */
    const void* next;
    uint32_t size;
    uint64_t frame_index; /* drives refresh clocks only; may skip */
    uint32_t reset;       /* non-zero: camera cut, every pixel misses */

    const float* depth;        /* width*height, in the context's depth mode; required */
    const float* reprojection; /* PREV_CLIP: 4 floats a pixel; MOTION: 2; MOTION_DEPTH: 3;
                                  CAMERA: ignored (NULL) */
    double view_proj[16];      /* CAMERA, and any frame of a context with a view_lobe (0.7): current view-projection, column-major (GLM), Vulkan clip */
    double prev_view_proj[16]; /* CAMERA: previous frame's */
    float jitter[2];           /* this frame's sample offset from the pixel centre, pixels, x right y down */
    float prev_jitter[2];      /* the previous frame's */
    const uint8_t* nocache;    /* width*height, non-zero = never a hit; required iff use_nocache_mask */

    uint32_t channel_count;            /* must equal the context's */
    const rrc_channel_input* channels; /* in the context's channel order */
    /* ---- 0.2 (a 0.1 caller's size ends before this: read as zero) ---- */
    const uint32_t* object_id; /* width*height object ids (any values); required iff use_object_id */
    /* ---- 0.3 ---- */
    uint32_t view;           /* the view this frame is: 0..view_count-1; its state becomes this frame */
    uint32_t reproject_from; /* 0: the view's own previous frame; v + 1: view v's latest frame (another
                                eye, the sub-frame before), which must have one (else every pixel misses) */
    /* ---- 0.7: read only when a channel has a view_lobe; then view_proj (above) is
     *      required whatever the reprojection source ---- */
    double camera_position[3];      /* this frame's eye, world space (the space view_proj maps from) */
    double prev_camera_position[3]; /* the eye of the frame reprojected from (reproject_from's) */
    /* ---- 0.8 (a 0.7 caller's size ends before this: read as zero) ---- */
    /* phi >= 0, radians, at most RRC_MAX_VIEW_LOBE: how far the distant lighting the
     * view lobes' channels reflect (a sky, an environment map) turned since the frame
     * reprojected from; 0 = still.  Their caps then use theta + phi
     * (docs/CONVENTIONS.md, "The view-dependent history").  Non-zero in a frame of a
     * context without a view_lobe is RRC_ERROR_INVALID_ARGUMENT. */
    float lighting_turn;
} rrc_frame_desc;

typedef struct rrc_frame_stats {
    uint64_t hits;
    uint64_t misses; /* non-background pixels that are neither hits nor refreshed */
    uint64_t background;
    uint64_t invalid_samples;  /* pixels with RRC_MASK_INVALID_SAMPLE */
    uint64_t invalid_geometry; /* pixels with RRC_MASK_INVALID_GEOMETRY */
} rrc_frame_stats;

/** Where one channel's results go; any pointer may be NULL (not read back). */
typedef struct rrc_channel_output {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_CHANNEL_OUTPUT */
    const void* next;
    uint32_t size;
    float* values; /* width*height*components: the accumulated signal (= next history); with a fill
                      (fill_age), the displayed value: filled where young, the history elsewhere */
    uint16_t* age; /* width*height: valid samples in history, 0 = empty */
    float* weight; /* width*height: accumulated confidence W (confidence channels only) */
} rrc_channel_output;

typedef struct rrc_frame_output {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_FRAME_OUTPUT */
    const void* next;
    uint32_t size;
    uint8_t* mask;          /* width*height RRC_MASK_* bits; may be NULL */
    uint32_t channel_count; /* 0 (no channel read back) or the context's */
    rrc_channel_output* channels;
    rrc_frame_stats stats; /* always written on success */
    /* ---- 0.3 (a 0.2 caller's size ends before this: not written) ---- */
    uint64_t refreshed; /* pixels with RRC_MASK_REFRESHED: passed the hit test but are re-shaded;
                           stats.hits + stats.misses + stats.background + refreshed = width * height */
} rrc_frame_output;

/** Runs one frame: uploads the inputs, dispatches the fused kernel, reads the
 *  requested outputs back, and waits.  The frame becomes the "previous frame"
 *  of the next call.  On error the history is unchanged. */
RRC_API rrc_result rrc_frame_run(rrc_context* context, const rrc_frame_desc* frame, rrc_frame_output* output);

/** Runs `count` frames in one submission: the same results as `count` calls of
 *  rrc_frame_run, with one upload, one wait and one readback for all (long
 *  offline runs, tests).  `outputs` is NULL or an array of `count`.  Every
 *  frame is validated before anything runs; on a validation error nothing
 *  changes.  Staging memory grows to the largest batch: count * (inputs + outputs). */
RRC_API rrc_result rrc_frame_run_batch(rrc_context* context, uint32_t count, const rrc_frame_desc* frames, rrc_frame_output* outputs);

/* ---- The shading cache, split in two (0.3; docs/guide/integration.md) -------- *
 * rrc_frame_run shades nothing for the host: it takes a sample at every
 * pixel.  A host whose shading is expensive runs each frame in two calls
 * instead, and shades only the quads classify lists:
 *
 *   rrc_frame_classify(ctx, &frame, &classified)   reproject, hit test, refresh
 *   ... the host shades every pixel of each listed 2x2 quad ...
 *   rrc_frame_resolve(ctx, &resolve, &output)      merge, update cache and age
 *
 * A quad is listed when one of its pixels is not a HIT (a miss, a refresh,
 * background or invalid geometry): exactly the pixels where a REUSE channel
 * takes the host's value.  Resolve gives the same results as rrc_frame_run
 * given the same values at the listed quads' pixels; what REUSE channels hold
 * elsewhere is never read.  Accumulating channels of the same context take a
 * sample at every pixel, so their arrays must be complete. */

/** Bytes of a quad list for a width x height context (rrc_values.h layout). */
#define RRC_QUAD_LIST_BYTES(width, height) \
    (4u * (RRC_QUAD_LIST_FIRST_QUAD + (((uint64_t)(width) + 1u) / 2u) * (((uint64_t)(height) + 1u) / 2u)))

typedef struct rrc_classify_output {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_CLASSIFY_OUTPUT */
    const void* next;
    uint32_t size;
    uint8_t* mask;          /* width*height RRC_MASK_* bits (INVALID_SAMPLE not yet known); may be NULL */
    uint32_t* quads;        /* quad_capacity words: the listed quads, x | y << 16, unordered; may be NULL */
    uint32_t quad_capacity; /* words at quads; fewer than quad_count is RRC_ERROR_SIZE_MISMATCH, nothing run */
    uint32_t quad_count;    /* written: the number of listed quads */
    rrc_frame_stats stats;  /* written: as rrc_frame_run's, invalid_samples 0 */
    uint64_t refreshed;     /* written: pixels with RRC_MASK_REFRESHED */
} rrc_classify_output;

typedef struct rrc_resolve_desc {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_RESOLVE_DESC */
    const void* next;
    uint32_t size;
    uint32_t channel_count;            /* the context's */
    const rrc_channel_input* channels; /* full-size arrays; a REUSE channel's are read at listed quads only */
} rrc_resolve_desc;

/** Classifies one frame: `frame` as for rrc_frame_run, except that its
 *  channels are not read (channel_count may be 0 and channels NULL).
 *  Writes the mask, the listed quads and the statistics, and keeps the
 *  classification for rrc_frame_resolve.  The history the next frame reads
 *  does not change until resolve (a context of REUSE channels only already
 *  computes its HITs' values here, into the image resolve completes).  A
 *  second classify, or rrc_frame_run, drops a classification not yet
 *  resolved; a classify that fails leaves the pending one as it was.
 *  quad_capacity = RRC_QUAD_LIST_BYTES(w, h) / 4 - RRC_QUAD_LIST_FIRST_QUAD
 *  always suffices. */
RRC_API rrc_result rrc_frame_classify(rrc_context* context, const rrc_frame_desc* frame, rrc_classify_output* output);

/** Completes the classified frame with the host's values: the frame becomes
 *  the "previous frame" of the next, as after rrc_frame_run.  Without a
 *  classification to complete: RRC_ERROR_INVALID_ARGUMENT. */
RRC_API rrc_result rrc_frame_resolve(rrc_context* context, const rrc_resolve_desc* resolve, rrc_frame_output* output);

#ifdef __cplusplus
}
#endif

#endif /* RRC_RRC_H */
