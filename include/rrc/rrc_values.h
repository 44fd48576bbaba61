/*
 * rrc — every value of the public enumerations and limits, written once.
 *
 * Preprocessor text only, readable as C99, C++ and GLSL: rrc.h expands these
 * lists into C enums (rrc_<type>_enum, see rrc.h); the library's GLSL kernels
 * (compute/rrc_values.glsl) and rrc-sample's shaders include this file and
 * expand the lists they need into `const uint` constants, so C and GLSL can
 * never disagree on a value.  Include <rrc/rrc.h>, not this file.
 *
 * Each list is a function-like macro RRC_<TYPE>_VALUES(X) that calls
 * X(NAME, value) once per value, in order.  Values are plain integer
 * literals (the C enums give them their type; GLSL converts them).  Only
 * comments and X(...) calls belong in a list: no C-only syntax here.
 */
#ifndef RRC_RRC_VALUES_H
#define RRC_RRC_VALUES_H

/* ---- rrc_result ---------------------------------------------------------- */
#define RRC_RESULT_VALUES(X)                                                                   \
    X(RRC_SUCCESS, 0)                                                                          \
    X(RRC_ERROR_INVALID_ARGUMENT, -1)     /* a NULL pointer, a bad value */                    \
    X(RRC_ERROR_INVALID_STRUCT, -2)       /* wrong type tag or size */                         \
    X(RRC_ERROR_INCOMPATIBLE_VERSION, -3) /* api_version of another major */                   \
    X(RRC_ERROR_UNSUPPORTED, -4)          /* valid, but not implemented or not on this device */ \
    X(RRC_ERROR_OUT_OF_MEMORY, -5)        /* host or device allocation failed */               \
    X(RRC_ERROR_DEVICE, -6)               /* no Vulkan device, or a Vulkan call failed */      \
    X(RRC_ERROR_DEVICE_LOST, -7)          /* the device was lost; destroy the context */       \
    X(RRC_ERROR_MISSING_INPUT, -8)        /* an input the configuration needs is NULL */       \
    X(RRC_ERROR_SIZE_MISMATCH, -9)        /* input sizes disagree with the context */          \
    X(RRC_ERROR_INVALID_HANDLE, -10)      /* NULL, destroyed or foreign context */

/* ---- rrc_depth_mode: how the depth the host passes is encoded ------------ */
#define RRC_DEPTH_MODE_VALUES(X)                                                        \
    X(RRC_DEPTH_MODE_STANDARD, 0) /* NDC z in [0,1], near 0, far 1; background = 1 */   \
    X(RRC_DEPTH_MODE_REVERSED, 1) /* NDC z, near 1, far 0 (far may be infinite); background = 0 */ \
    X(RRC_DEPTH_MODE_LINEAR, 2)   /* planar view depth (clip w); background = +inf or >= threshold */

/* ---- rrc_depth_format: sets epsilon, "the smallest z increment" ---------- */
#define RRC_DEPTH_FORMAT_VALUES(X)                                              \
    X(RRC_DEPTH_FORMAT_FLOAT32, 0) /* eps = scale * ulp(z), default scale 4 */  \
    X(RRC_DEPTH_FORMAT_UNORM16, 1) /* eps = scale / 65535, default scale 1 */   \
    X(RRC_DEPTH_FORMAT_UNORM24, 2) /* eps = scale / 16777215, default scale 1 */

/* ---- rrc_depth_test: which epsilon-depth test decides a hit ------------- */
#define RRC_DEPTH_TEST_VALUES(X)                                                              \
    X(RRC_DEPTH_TEST_DEFAULT, 0)  /* ADAPTIVE (0.2 callers, no eps/tau set), else FIXED */       \
    X(RRC_DEPTH_TEST_ADAPTIVE, 1) /* paper eps + capped bilinear-residual bound (CONVENTIONS.md) */ \
    X(RRC_DEPTH_TEST_FIXED, 2)    /* the paper's test exactly: |diff| <= eps (or tau*d) */

/* ---- rrc_reprojection: where each pixel's previous position comes from -- */
#define RRC_REPROJECTION_VALUES(X)                                                                  \
    X(RRC_REPROJECTION_PREV_CLIP, 0)    /* RGBA32F previous clip position (x,y,z,w) per pixel */     \
    X(RRC_REPROJECTION_MOTION, 1)       /* RG: uv_prev - uv_cur (times motion_scale) */              \
    X(RRC_REPROJECTION_MOTION_DEPTH, 2) /* RGB: as MOTION plus expected prev depth - current depth */ \
    X(RRC_REPROJECTION_CAMERA, 3)       /* no per-pixel data: view-projection matrices (static scenes) */

/* ---- rrc_blend: the lambda recursive filter's blend ---------------------- */
#define RRC_BLEND_VALUES(X)                                          \
    X(RRC_BLEND_FIXED, 0)        /* lambda_eff = lambda (the paper) */ \
    X(RRC_BLEND_AGE_AWARE, 1)    /* lambda_eff = min(lambda, n/(n+1)) */ \
    X(RRC_BLEND_RUNNING_MEAN, 2) /* lambda_eff = n/(n+1): mean of all samples since the last miss */ \
    X(RRC_BLEND_REUSE, 3)        /* shading cache: a hit keeps the resampled cached value, a miss or refresh takes s */

/* ---- rrc_refresh_policy: which hits a REUSE channel re-shades anyway ----- */
#define RRC_REFRESH_POLICY_VALUES(X)                                                                   \
    X(RRC_REFRESH_NONE, 0)   /* only misses are re-shaded (and max_lifetime, if set) */                \
    X(RRC_REFRESH_TILED, 1)  /* gx x gy screen tiles; tile i = tx + gx*ty when (t + i) mod n = 0 */     \
    X(RRC_REFRESH_RANDOM, 2) /* each 2x2 quad at offset d (balanced hash) when (t + d) mod n = 0 */

/* ---- rrc_history_filter: how history is resampled ------------------------ */
#define RRC_HISTORY_FILTER_VALUES(X)                                    \
    X(RRC_HISTORY_FILTER_BILINEAR, 0) /* the paper's choice (default) */ \
    X(RRC_HISTORY_FILTER_NEAREST, 1)                                    \
    X(RRC_HISTORY_FILTER_CATMULL_ROM, 2) /* clamped to the 4 bilinear taps' range: cannot ring */ \
    X(RRC_HISTORY_FILTER_GAUSSIAN, 3)    /* bilinear after a 3-tap blur of variance blur_sigma^2 (PCF's post step) */

/* ---- rrc_history_precision ----------------------------------------------- */
#define RRC_HISTORY_PRECISION_VALUES(X)                                           \
    X(RRC_HISTORY_FP16, 0) /* RGBA16F/R16F history, rounded to nearest in the shader */ \
    X(RRC_HISTORY_FP32, 1)

/* ---- Bits of the per-pixel mask (rrc_frame_output.mask, uint8_t) --------- */
#define RRC_MASK_VALUES(X)                                                       \
    X(RRC_MASK_HIT, 1)                                                           \
    X(RRC_MASK_REFRESHED, 2)                                                     \
    X(RRC_MASK_BACKGROUND, 4)                                                    \
    X(RRC_MASK_INVALID_SAMPLE, 8)    /* some channel's sample was not finite */   \
    X(RRC_MASK_INVALID_GEOMETRY, 16) /* non-finite depth or reprojection data */

/* ---- rrc_preset: one application's settings (rrc_channel_preset; docs/guide/) */
#define RRC_PRESET_VALUES(X)                                                                          \
    X(RRC_PRESET_PCF_SHADOWS, 1)   /* amortized PCF: each frame k random shadow-map compares */        \
    X(RRC_PRESET_ENV_BUMP, 2)      /* env-mapped bump mapping: each frame k reflections of the footprint */ \
    X(RRC_PRESET_SOFT_SHADOWS, 3)  /* area-light soft shadows: each frame one light point's shadow */ \
    X(RRC_PRESET_SHADING_CACHE, 4) /* the shading cache: shade only the misses (REUSE) */            \
    X(RRC_PRESET_OFFLINE, 5)       /* path-traced sequences (Cycles passes: linear depth, pixel motion) */

/* ---- rrc_log_level ------------------------------------------------------- */
#define RRC_LOG_LEVEL_VALUES(X) \
    X(RRC_LOG_INFO, 0)          \
    X(RRC_LOG_WARNING, 1)       \
    X(RRC_LOG_ERROR, 2)         \
    X(RRC_LOG_VALIDATION, 3) /* a message of the Khronos validation layer */

/* ---- Limits -------------------------------------------------------------- */

/** Channels a context may hold (one fused dispatch serves them all). */
#define RRC_MAX_CHANNELS 4
/** Longest channel name, including the terminating NUL. */
#define RRC_MAX_NAME 64
/** Largest age cap: ages are stored as 16-bit unsigned integers. */
#define RRC_MAX_AGE_CAP 65535u
/** Largest width or height of a context. */
#define RRC_MAX_EXTENT 16384u
/** Views a context may hold (stereo eyes, motion-blur sub-frames, lens samples). */
#define RRC_MAX_VIEWS 4u
/** Largest refresh period n, and largest tile count along one axis (TILED). */
#define RRC_MAX_REFRESH_PERIOD 65536u
#define RRC_MAX_REFRESH_TILES 256u

/* ---- The quad list of classify (docs/guide/integration.md, "The shading cache: shade only the misses") ----
 * uint32 words: [0] the number of listed quads, [1..3] a
 * VkDispatchIndirectCommand {x, y, z} = {ceil(count / RRC_QUADS_PER_GROUP),
 * 1, 1}, then from word RRC_QUAD_LIST_FIRST_QUAD one word per listed quad,
 * x | y << 16, where (x, y) is the quad's index: it covers the pixels
 * (2x..2x+1, 2y..2y+1).  The order of the quads is unspecified. */
#define RRC_QUADS_PER_GROUP 64u
#define RRC_QUAD_LIST_COUNT 0u
#define RRC_QUAD_LIST_DISPATCH 1u
#define RRC_QUAD_LIST_FIRST_QUAD 4u

#endif /* RRC_RRC_VALUES_H */
