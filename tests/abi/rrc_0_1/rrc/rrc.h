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
 * Lifetime
 * --------
 *   rrc_validate_context_desc()  check a descriptor; no Vulkan object made
 *   rrc_context_create()         make a context (and, standalone, a device)
 *   rrc_frame_run()              per frame: CPU arrays in, CPU arrays out
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
 * threads at once.  Distinct contexts are independent and may be driven from
 * different threads concurrently.  rrc_validate_context_desc(),
 * rrc_get_version() and rrc_result_to_string() are thread-safe.
 *
 * Versioning
 * ----------
 * RRC_API_VERSION encodes major.minor.patch.  Callers put the version they
 * compiled against in rrc_context_desc.api_version; create refuses another
 * major version (RRC_ERROR_INCOMPATIBLE_VERSION).  Within a major version the
 * API only grows: structs start with a type tag, a `next` pointer and their
 * size, new members are appended, and a zeroed member always means the old
 * default behaviour.
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
#  if defined(RRC_BUILDING_LIBRARY)
#    define RRC_API __declspec(dllexport)
#  else
#    define RRC_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__)
#  define RRC_API __attribute__((visibility("default")))
#else
#  define RRC_API
#endif

/* ---- Version ----------------------------------------------------------- */

#define RRC_MAKE_VERSION(major, minor, patch) \
    ((((uint32_t)(major)) << 22) | (((uint32_t)(minor)) << 12) | ((uint32_t)(patch)))
#define RRC_VERSION_MAJOR(v) ((uint32_t)(v) >> 22)
#define RRC_VERSION_MINOR(v) (((uint32_t)(v) >> 12) & 0x3FFu)
#define RRC_VERSION_PATCH(v) ((uint32_t)(v)&0xFFFu)

/** The version of this header. */
#define RRC_API_VERSION RRC_MAKE_VERSION(0, 1, 0)

/** The version of the library actually loaded. */
RRC_API uint32_t rrc_get_version(void);

/* ---- Results ----------------------------------------------------------- */

typedef int32_t rrc_result;
#define RRC_SUCCESS 0
#define RRC_ERROR_INVALID_ARGUMENT -1       /* a NULL pointer, a bad value */
#define RRC_ERROR_INVALID_STRUCT -2         /* wrong type tag or size */
#define RRC_ERROR_INCOMPATIBLE_VERSION -3   /* api_version of another major */
#define RRC_ERROR_UNSUPPORTED -4            /* valid, but not implemented or not on this device */
#define RRC_ERROR_OUT_OF_MEMORY -5          /* host or device allocation failed */
#define RRC_ERROR_DEVICE -6                 /* no Vulkan device, or a Vulkan call failed */
#define RRC_ERROR_DEVICE_LOST -7            /* the device was lost; destroy the context */
#define RRC_ERROR_MISSING_INPUT -8          /* an input the configuration needs is NULL */
#define RRC_ERROR_SIZE_MISMATCH -9          /* input sizes disagree with the context */
#define RRC_ERROR_INVALID_HANDLE -10        /* NULL, destroyed or foreign context */

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

/* ---- Enumerations (stored as uint32_t; 0 is the default) --------------- */

/** How the depth the host passes is encoded (docs/CONVENTIONS.md §depth). */
typedef uint32_t rrc_depth_mode;
#define RRC_DEPTH_MODE_STANDARD 0 /* NDC z in [0,1], near 0, far 1; background = 1 */
#define RRC_DEPTH_MODE_REVERSED 1 /* NDC z, near 1, far 0 (far may be infinite); background = 0 */
#define RRC_DEPTH_MODE_LINEAR 2   /* planar view depth (clip w); background = +inf or >= threshold */

/** The host's depth-buffer format: sets epsilon, "the smallest z increment". */
typedef uint32_t rrc_depth_format;
#define RRC_DEPTH_FORMAT_FLOAT32 0 /* eps = scale * ulp(z), default scale 4 */
#define RRC_DEPTH_FORMAT_UNORM16 1 /* eps = scale / 65535, default scale 1 */
#define RRC_DEPTH_FORMAT_UNORM24 2 /* eps = scale / 16777215, default scale 1 */

/** Where the previous-frame position of each pixel comes from. */
typedef uint32_t rrc_reprojection;
#define RRC_REPROJECTION_PREV_CLIP 0 /* RGBA32F previous clip position (x,y,z,w) per pixel */
#define RRC_REPROJECTION_MOTION 1    /* RG: uv_prev - uv_cur (times motion_scale) */
#define RRC_REPROJECTION_MOTION_DEPTH 2 /* RGB: as MOTION plus expected prev depth - current depth */
#define RRC_REPROJECTION_CAMERA 3    /* no per-pixel data: view-projection matrices (static scenes) */

/** The lambda recursive filter's blend (docs/CONVENTIONS.md §filter). */
typedef uint32_t rrc_blend;
#define RRC_BLEND_FIXED 0        /* lambda_eff = lambda (the paper) */
#define RRC_BLEND_AGE_AWARE 1    /* lambda_eff = min(lambda, n/(n+1)) */
#define RRC_BLEND_RUNNING_MEAN 2 /* lambda_eff = n/(n+1): mean of all samples since the last miss */

/** How history is resampled at the reprojected position. */
typedef uint32_t rrc_history_filter;
#define RRC_HISTORY_FILTER_BILINEAR 0    /* the paper's choice (default) */
#define RRC_HISTORY_FILTER_NEAREST 1
#define RRC_HISTORY_FILTER_CATMULL_ROM 2 /* clamped to the 4 bilinear taps' range: cannot ring */

typedef uint32_t rrc_history_precision;
#define RRC_HISTORY_FP16 0 /* RGBA16F/R16F history, rounded to nearest in the shader */
#define RRC_HISTORY_FP32 1
/** fp16 history is kept only while the largest effective lambda a channel can
 *  reach (FIXED: lambda; AGE_AWARE: min(lambda, cap/(cap+1)); RUNNING_MEAN:
 *  cap/(cap+1)) is at most this; above it the channel's history is fp32.
 *  Why: a history rounded to nearest fp16 stops moving once
 *  (1 - lambda)|s - H| < ulp(H)/2, i.e. it may stall up to 2^-11/(1 - lambda)
 *  of H away from the signal (bias 3.6e-2 at lambda 0.999 on a noisy signal;
 *  docs/STABILITY.md). */
#define RRC_FP16_MAX_LAMBDA 0.95

/** Bits of the per-pixel mask. */
#define RRC_MASK_HIT 1u
#define RRC_MASK_REFRESHED 2u
#define RRC_MASK_BACKGROUND 4u
#define RRC_MASK_INVALID_SAMPLE 8u   /* some channel's sample was not finite */
#define RRC_MASK_INVALID_GEOMETRY 16u /* non-finite depth or reprojection data */

/** Channels a context may hold (one fused dispatch serves them all). */
#define RRC_MAX_CHANNELS 4
/** Longest channel name, including the terminating NUL. */
#define RRC_MAX_NAME 64
/** Largest age cap: ages are stored as 16-bit unsigned integers. */
#define RRC_MAX_AGE_CAP 65535u
/** Largest width or height of a context. */
#define RRC_MAX_EXTENT 16384u

/* ---- Logging ----------------------------------------------------------- */

typedef uint32_t rrc_log_level;
#define RRC_LOG_INFO 0
#define RRC_LOG_WARNING 1
#define RRC_LOG_ERROR 2
#define RRC_LOG_VALIDATION 3 /* a message of the Khronos validation layer */

/** Receives UTF-8, NUL-terminated text valid only during the call. */
typedef void (*rrc_log_fn)(void* user, rrc_log_level level, const char* message);

/* ---- Context description ----------------------------------------------- */

/** One accumulated signal. */
typedef struct rrc_channel_desc {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_CHANNEL_DESC */
    const void* next;     /* reserved, must be NULL */
    uint32_t size;        /* sizeof(rrc_channel_desc) */
    char name[RRC_MAX_NAME]; /* non-empty, unique in the context, NUL-terminated */
    uint32_t components;  /* 1 or 4 */
    rrc_history_precision precision; /* fp16 (default) or fp32; fp16 above RRC_FP16_MAX_LAMBDA is fp32 */
    float lambda;         /* in [0,1); the weight of history. 0 with blend FIXED is no accumulation */
    rrc_blend blend;
    rrc_history_filter filter;
    uint32_t age_cap;     /* saturation of the age count; 0 = default 255, at most RRC_MAX_AGE_CAP */
    uint32_t confidence;  /* non-zero: the host passes a per-sample weight w in [0,1] */
} rrc_channel_desc;

typedef struct rrc_context_desc {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_CONTEXT_DESC */
    const void* next;     /* reserved, must be NULL */
    uint32_t size;        /* sizeof(rrc_context_desc) */
    uint32_t api_version; /* RRC_API_VERSION the caller compiled against */

    uint32_t width, height; /* 1..RRC_MAX_EXTENT */

    rrc_depth_mode depth_mode;
    float near_plane;     /* view distance of the near plane; needed by MOTION with NDC depth */
    float far_plane;      /* may be +inf (REVERSED); needed by MOTION with NDC depth */
    float background_threshold; /* LINEAR: d >= this is background; 0 = default 1e10 */

    rrc_depth_format depth_format; /* NDC modes: which z increment makes epsilon */
    float epsilon_scale;  /* epsilon = scale * increment; 0 = default (1 unorm, 4 float32) */
    float epsilon;        /* > 0: absolute epsilon (NDC modes), overrides format and scale */
    float tau;            /* relative tolerance |diff| <= tau*d for LINEAR and linearised
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

    rrc_log_fn log;       /* optional */
    void* log_user;       /* passed to log */
} rrc_context_desc;

/** Check a context descriptor without touching Vulkan.  Returns RRC_SUCCESS or
 *  the code create would fail with; the message (naming the field) is
 *  available from rrc_last_error().  Cheap: fuzzers call it many times. */
RRC_API rrc_result rrc_validate_context_desc(const rrc_context_desc* desc);

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
 *  its own input copies and staging), in bytes. */
RRC_API rrc_result rrc_get_memory_usage(const rrc_context* context, uint64_t* out_bytes);

/** Number of validation-layer messages seen so far (0 if validation is off). */
RRC_API rrc_result rrc_context_validation_messages(const rrc_context* context, uint64_t* out_count);

/* ---- Frames (standalone: CPU arrays) ----------------------------------- */

/** One channel's per-frame input.  Arrays are row-major, row 0 at the top. */
typedef struct rrc_channel_input {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_CHANNEL_INPUT */
    const void* next;
    uint32_t size;
    const float* samples;    /* width*height*components, interleaved; required */
    const float* confidence; /* width*height weights in [0,1]; required iff the channel has confidence */
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
    double view_proj[16];      /* CAMERA: current view-projection, column-major (GLM), Vulkan clip */
    double prev_view_proj[16]; /* CAMERA: previous frame's */
    float jitter[2];           /* this frame's sample offset from the pixel centre, pixels, x right y down */
    float prev_jitter[2];      /* the previous frame's */
    const uint8_t* nocache;    /* width*height, non-zero = never a hit; required iff use_nocache_mask */

    uint32_t channel_count;            /* must equal the context's */
    const rrc_channel_input* channels; /* in the context's channel order */
} rrc_frame_desc;

typedef struct rrc_frame_stats {
    uint64_t hits;
    uint64_t misses;     /* non-background pixels that are not hits */
    uint64_t background;
    uint64_t invalid_samples;  /* pixels with RRC_MASK_INVALID_SAMPLE */
    uint64_t invalid_geometry; /* pixels with RRC_MASK_INVALID_GEOMETRY */
} rrc_frame_stats;

/** Where one channel's results go; any pointer may be NULL (not read back). */
typedef struct rrc_channel_output {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_CHANNEL_OUTPUT */
    const void* next;
    uint32_t size;
    float* values; /* width*height*components: the accumulated signal (= next history) */
    uint16_t* age; /* width*height: valid samples in history, 0 = empty */
    float* weight; /* width*height: accumulated confidence W (confidence channels only) */
} rrc_channel_output;

typedef struct rrc_frame_output {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_FRAME_OUTPUT */
    const void* next;
    uint32_t size;
    uint8_t* mask;        /* width*height RRC_MASK_* bits; may be NULL */
    uint32_t channel_count; /* 0 (no channel read back) or the context's */
    rrc_channel_output* channels;
    rrc_frame_stats stats; /* always written on success */
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
RRC_API rrc_result rrc_frame_run_batch(rrc_context* context, uint32_t count, const rrc_frame_desc* frames,
                                       rrc_frame_output* outputs);

#ifdef __cplusplus
}
#endif

#endif /* RRC_RRC_H */
