// The interface between the kernels (compute/rrc_module_*.comp and their
// includes) and the library (plugin/accumulate_pipeline.h/.cpp,
// plugin/config.h), written once: specialization-constant ids, descriptor
// binding numbers, epsilon kinds and the push-constant layout.  Preprocessor
// text only, read by GLSL and C++ alike; not a public header.  The values of
// the public enumerations are in include/rrc/rrc_values.h.
#ifndef RRC_KERNEL_INTERFACE_H
#define RRC_KERNEL_INTERFACE_H

// ---- Specialization constant ids: one range, 0..RRC_SPEC_COUNT - 1 --------
// Only what changes code is a specialization constant: sources, modes,
// passes, masks, the shading cache's clocks and each channel slot's feature
// word.  A channel's parameters (lambda, thresholds, widths: what changes no
// code) are in its parameter block, RRC_BINDING_CHANNEL_PARAMS below.
// Whole-dispatch constants (rrc_depth.glsl, rrc_reproject.glsl, the passes).
#define RRC_SPEC_SOURCE 0         // uint rrc_reprojection
#define RRC_SPEC_DEPTH_MODE 1     // uint rrc_depth_mode
#define RRC_SPEC_EPS_KIND 2       // uint RRC_EPS_* below
#define RRC_SPEC_HAS_NOCACHE 3    // bool: frames carry a do-not-cache mask
#define RRC_SPEC_CHANNEL_COUNT 4  // uint 1..RRC_MAX_CHANNELS
#define RRC_SPEC_INTEROP 5        // bool: host images through samplers
#define RRC_SPEC_STATS 6          // bool: count the frame's statistics into RRC_BINDING_STATS (interop)
#define RRC_SPEC_HOST_AGE_MASK 7  // uint: bit c = channel slot c also writes its age to the host's image (interop)
#define RRC_SPEC_ADAPTIVE 8       // bool: the ADAPTIVE depth test (not plain MOTION; below)
#define RRC_SPEC_OBJECT_ID 9      // bool: frames carry object ids (RRC_BINDING_OBJECT_ID..)
#define RRC_SPEC_STORAGE_INPUTS 10  // bool: interop, the host's inputs read as storage images (rrc_vulkan_frame_desc.storage_inputs)
#define RRC_SPEC_PASS 11           // uint RRC_PASS_* below: the pass this pipeline runs
#define RRC_SPEC_HOST_OUT_MASK 12   // uint: bit c = channel slot c writes RRC_BINDING_HOST_OUT in this pass (plugin/frame_plan.cpp decides)
#define RRC_SPEC_COPY_MASK 13       // bool: COPY_OUT also copies the classified mask into RRC_BINDING_MASK (the host's)
#define RRC_SPEC_MASK_IN_PLACE 14   // bool: LIST / RESOLVE / RESOLVE_LISTED read classify's mask from RRC_BINDING_MASK (the image classify wrote), not RRC_BINDING_CLASSIFIED
// The shading cache's constants (compute/rrc_cache.glsl): the refresh clock's
// modulus and tiles shape its arithmetic.
#define RRC_SPEC_REFRESH_POLICY 15   // uint rrc_refresh_policy
#define RRC_SPEC_REFRESH_PERIOD 16   // uint n
#define RRC_SPEC_REFRESH_TILES_X 17  // uint gx (TILED)
#define RRC_SPEC_REFRESH_TILES_Y 18  // uint gy (TILED)
#define RRC_SPEC_MAX_LIFETIME 19     // uint L, 0 = none
#define RRC_SPEC_GROUP_SIZE_X 20  // local_size_x_id
#define RRC_SPEC_GROUP_SIZE_Y 21  // local_size_y_id
// Channel slot c's feature word: id RRC_SPEC_CHANNEL_FEATURES + c.  Its
// fields are the `bit, width` columns of rrc_channel_options.def (the
// components, precision, blend, filter, each optional step, the fill's
// radius); rrc_channel_slots.glsl reads them.
#define RRC_SPEC_CHANNEL_FEATURES 22
#define RRC_SPEC_CHANNEL_SLOTS 4
#define RRC_SPEC_COUNT_IO 26  // bool: count the image loads and stores into RRC_BINDING_STATS after the statistics (compute/rrc_io.glsl)
#define RRC_SPEC_COUNT 27
// The feature word of a default channel (rrc_create's defaults: 1 component,
// fp16, FIXED, BILINEAR, nothing optional): the constants' default value.
#define RRC_DEFAULT_CHANNEL_FEATURES 2u
// The channel parameter block (RRC_BINDING_CHANNEL_PARAMS): std140, one
// struct a slot with one 32-bit member a PARAM row of rrc_channel_options.def,
// in row order, its stride a multiple of 16 bytes.
// The lag detector's darkness term: added to the relative gap's denominator so
// that a history and a signal both near 0 do not make a large relative gap
// (docs/CONVENTIONS.md, "The lag detector").
#define RRC_ANTILAG_DARKNESS 1e-3

// ---- Passes (the value of RRC_SPEC_PASS) ----------------------------------
// Which passes a frame runs, in which order, over which grid, is decided in
// one place: plugin/frame_plan.cpp (docs/design/frame-plan.md).
#define RRC_PASS_FUSED 0u     // rrc_frame_run / rrc_vulkan_record_frame: one pass, a dispatch over pixels
#define RRC_PASS_CLASSIFY 1u  // classify, first dispatch: the mask, over pixels; in a context of REUSE channels only, also every HIT's channels
#define RRC_PASS_LIST 2u      // classify, second dispatch: the quad list from that mask, over 2x2 quads
#define RRC_PASS_RESOLVE 3u   // the channels with classify's mask: a dispatch over pixels, no hit test
#define RRC_PASS_FILL 4u      // the spatial fill: after the frame, indirect over the fill list, bound as the next frame (docs/CONVENTIONS.md)
#define RRC_PASS_RESOLVE_LISTED 5u  // resolve of a context of REUSE channels only: indirect over the quad list, the listed pixels that are not HITs
#define RRC_PASS_COPY_OUT 6u  // after RESOLVE_LISTED: the library's results into the host's output, age and mask images, over pixels, bound as the next frame

// ---- Descriptor bindings (set 0) -------------------------------------------
// Geometry (rrc_reproject.glsl) and the mask: one image each.
#define RRC_BINDING_DEPTH 0
#define RRC_BINDING_PREV_DEPTH 1
#define RRC_BINDING_REPROJ 2          // the library's RGBA32F copy: PREV_CLIP, MOTION (.xy), MOTION_DEPTH (.xyz)
#define RRC_BINDING_PREV_OBJECT_ID 3  // R32_UINT: the previous frame's object ids (the other parity)
#define RRC_BINDING_NOCACHE 4
#define RRC_BINDING_MASK 5
#define RRC_BINDING_HOST_DEPTH 6    // interop: sampler
#define RRC_BINDING_HOST_REPROJ 7   // interop: sampler
#define RRC_BINDING_HOST_NOCACHE 8  // interop: sampler
#define RRC_BINDING_DEPTH_OUT 9     // interop: next frame's previous depth
// Per channel (rrc_channel_slots.glsl): arrays of RRC_MAX_CHANNELS, indexed by slot.
#define RRC_BINDING_SAMPLE1 10
#define RRC_BINDING_SAMPLE4 11
#define RRC_BINDING_CONFIDENCE 12
#define RRC_BINDING_HIST_PACKED 13  // R32_UINT: fp16 value (low half) | age << 16, the 1-component fp16 channels
#define RRC_BINDING_HIST_RGBA16F 14
#define RRC_BINDING_HIST_R32F 15
#define RRC_BINDING_HIST_RGBA32F 16
#define RRC_BINDING_AGE 17
#define RRC_BINDING_WEIGHT 18
#define RRC_BINDING_HIST_OUT 19
#define RRC_BINDING_AGE_OUT 20
#define RRC_BINDING_WEIGHT_OUT 21
#define RRC_BINDING_HOST_SAMPLES 22     // interop: sampler
#define RRC_BINDING_HOST_CONFIDENCE 23  // interop: sampler
#define RRC_BINDING_HOST_OUT 24         // interop: the host's output image
#define RRC_BINDING_HOST_AGE_OUT 25     // interop: the host's age image (optional)
#define RRC_BINDING_FIRST_CHANNEL RRC_BINDING_SAMPLE1
#define RRC_BINDING_LAST_CHANNEL RRC_BINDING_HOST_AGE_OUT
// Object ids (RRC_SPEC_OBJECT_ID): one image each.
#define RRC_BINDING_OBJECT_ID 26       // interop: R32_UINT, the kernel's copy of this frame's ids for the next
#define RRC_BINDING_HOST_OBJECT_ID 27  // sampler: this frame's ids (standalone: the upload; interop: the host's image)
// Resolve reads the mask classify wrote (R8_UINT, the library's own mask)
// through a sampler: the storage images are at lavapipe's 64 a stage already.
#define RRC_BINDING_CLASSIFIED 28
// The spatial fill's fallback estimates (0.4), per channel slot: samplers
// (the host's images, or the standalone uploads), read by the FILL pass only.
#define RRC_BINDING_FALLBACK 29
// The deviation gate's previous state (0.12, docs/CONVENTIONS.md "The
// deviation gate"), per channel slot: fp16 (beta, sqrt(varsigma)) read as
// one R32_UINT word a texel through a sampler, the storage images being at
// lavapipe's 64 a stage; the state is written as R16G16_SFLOAT through
// RRC_BINDING_WEIGHT_OUT (a gated channel has no confidence weight).
#define RRC_BINDING_GATE 30
#define RRC_BINDING_LAST RRC_BINDING_GATE
// The buffer bindings, after every image binding: the host's statistics
// buffer (interop, rrc_vulkan_frame_stats; std430 uint[8]) and classify's
// quad list (include/rrc/rrc_values.h layout).
#define RRC_BINDING_STATS 31
#define RRC_BINDING_QUADS 32
// The fill list (library-owned): the pixels the spatial fill runs on,
// appended by the pass that writes their channels (docs/CONVENTIONS.md,
// "The spatial fill"), in RRC_FILL_LISTS sub-lists, one a band of rows, so
// that the appends do not all contend for one counter
// (docs/design/frame-plan.md): a VkDispatchIndirectCommand {the sub-lists'
// groups of RRC_FILL_LIST_PER_GROUP pixels, 1, 1}, each sub-list's count on a
// 64-byte line of its own, then the sub-lists, RRC_FILL_LIST_CAPACITY words
// each, one word x | y << 16 a pixel.
#define RRC_BINDING_FILL_LIST 33
// The view buffer (library-owned, RRC_SPEC_VIEW_LOBE contexts only): this
// frame's camera for the view lobe, std430 { mat4 Q; vec4 d; }: Q =
// translate(-C) * inverse(VP_cur) (the pixel's clip position to its surface
// point relative to the eye, homogeneous), d.xyz = C_prev - C, d.w = the
// lighting's turn phi (rrc_frame_desc.lighting_turn, 0.8); formed in
// double on the CPU and written by the frame's own commands
// (plugin/accumulator_core.cpp).  Bound to every per-pixel pass.
#define RRC_BINDING_VIEW 34
#define RRC_VIEW_BUFFER_FLOATS 20
// The channel parameter block (library-owned, a uniform buffer written once
// at creation): each slot's PARAM rows (rrc_channel_options.def).  Bound to
// the passes that run channels (frame, fill).
#define RRC_BINDING_CHANNEL_PARAMS 35
#define RRC_FILL_LIST_DISPATCH 0u
#define RRC_FILL_LISTS 16u
#define RRC_FILL_LIST_COUNTS 16u        // sub-list k's count: word RRC_FILL_LIST_COUNTS + k * RRC_FILL_LIST_COUNT_STRIDE
#define RRC_FILL_LIST_COUNT_STRIDE 16u  // words: one 64-byte line a count
#define RRC_FILL_LIST_FIRST (RRC_FILL_LIST_COUNTS + RRC_FILL_LISTS * RRC_FILL_LIST_COUNT_STRIDE)
#define RRC_FILL_LIST_PER_GROUP 128u  // the kernel's workgroup width (plugin/accumulate_pipeline.h kGroupX)
// Row y of an h-row frame goes to sub-list y / RRC_FILL_LIST_BAND(h): a band
// of rows a sub-list, so that each sub-list is in raster order and workers
// that take the frame's workgroups in ranges append to different ones.  A
// sub-list's capacity, in words, for a w x h frame: its band's pixels.
#define RRC_FILL_LIST_BAND(h) (((h) + RRC_FILL_LISTS - 1u) / RRC_FILL_LISTS)
#define RRC_FILL_LIST_CAPACITY(w, h) (RRC_FILL_LIST_BAND(h) * (w))
// Counter indices in it (the member order of rrc_vulkan_frame_stats).
#define RRC_STAT_HITS 0
#define RRC_STAT_MISSES 1
#define RRC_STAT_BACKGROUND 2
#define RRC_STAT_INVALID_SAMPLES 3
#define RRC_STAT_INVALID_GEOMETRY 4
#define RRC_STAT_REFRESHED 5
#define RRC_STAT_PIXELS 6
#define RRC_STAT_COUNT 8
// With RRC_SPEC_COUNT_IO, the words after the statistics: rrc_vulkan_io_counts
// (include/rrc/rrc_vulkan.h), five 64-bit counters as (low, high) word pairs.
#define RRC_IO_LOADS 0
#define RRC_IO_TEXELS 1
#define RRC_IO_LOAD_BYTES 2
#define RRC_IO_STORES 3
#define RRC_IO_STORE_BYTES 4
#define RRC_IO_COUNTERS 5
#define RRC_IO_WORD(counter) (RRC_STAT_COUNT + 2 * (counter))  // its low word; the high word follows

// ---- Epsilon kinds (the value of RRC_SPEC_EPS_KIND) ------------------------
#define RRC_EPS_ABSOLUTE 0u  // pc.eps is epsilon itself
#define RRC_EPS_ULP 1u       // pc.eps is a scale of ulp(expected depth)
#define RRC_EPS_RELATIVE 2u  // pc.eps is tau: |diff| <= tau * expected linear depth

// ---- The ADAPTIVE depth test (docs/CONVENTIONS.md, "The ADAPTIVE test") ---
// eps = max(eps_paper, FLOOR_ULPS ulp(e)) + min(CAP * |e - z_inf|,
//         GAIN * ((fx(1-fx) + fy(1-fy)) C + ox Sx + oy Sy)
//         + POSITION_ULPS 2^-24 (width Sx + height Sy))  [+ CAMERA's allowance],
// C from the current depth's second differences (5 taps an axis): per axis the
// centre's, or at a step of its own the smooth side's, less NOISE_ULPS *
// ulp(largest tap) + NOISE_STEPS * the format's step; an axis beside a step
// borrows the other's only below BORROW of that step, both beside steps give
// 0; o = overhang beyond the outermost texel centres, S = slope.
#define RRC_ADAPTIVE_GAIN 2.0         // 4x the Taylor residual f(1-f) z''/2: margin for grid motion, kinks, higher orders
#define RRC_ADAPTIVE_STEP_RATIO 0.5   // beside a step: a neighbouring second difference of the other sign, at least this share of it
#define RRC_ADAPTIVE_STEP_OWN 0.5     // a step of its own: the centre's second difference or slope towards it is at least this share of it
#define RRC_ADAPTIVE_SMOOTH_SIDE 0.25  // a step's smooth side: a neighbour not of the other sign, at most this share of the centre's
#define RRC_ADAPTIVE_BORROW 0.5        // beside a step, the other axis's curvature counts only up to this share of the step
#define RRC_ADAPTIVE_CAP 0.04         // of |z - z_inf|: 4% of the linear depth on infinite projections
#define RRC_ADAPTIVE_POSITION_ULPS 8.0  // the kernel's fp32 error of q, in units of 2^-24 * size texels (times the slope)
#define RRC_ADAPTIVE_CAMERA_ULPS 4.0    // CAMERA: fp32 error of e = (M p).z / w, in units of 2^-24 * sum |M_2k p_k| / w
#define RRC_ADAPTIVE_FLOOR_ULPS 4.0   // NDC tests: eps_paper is at least this many ulp(e), the kernel's own fp32 noise
#define RRC_ADAPTIVE_NOISE_ULPS 4.0   // bound of fp32 storage + arithmetic error of a second difference
#define RRC_ADAPTIVE_NOISE_STEPS 2.0  // bound of UNORM quantisation error of a second difference

// ---- Push constants: byte offsets of the members of `Frame` ----------------
// (rrc_reproject.glsl declares each member at its offset; the C++ mirror
// FramePushConstants static_asserts each one.)  128 bytes: fills the 128-byte
// minimum of maxPushConstantsSize exactly.
#define RRC_PC_OFFSET_M 0               // mat4
#define RRC_PC_OFFSET_INV_ROW3 64       // vec4
#define RRC_PC_OFFSET_JITTER 80         // vec4
#define RRC_PC_OFFSET_MOTION_SCALE 96   // vec2
#define RRC_PC_OFFSET_EPS 104           // float
#define RRC_PC_OFFSET_NEAR_PLANE 108    // float
#define RRC_PC_OFFSET_FAR_PLANE 112     // float
#define RRC_PC_OFFSET_BG_THRESHOLD 116  // float
#define RRC_PC_OFFSET_PREV_VALID 120    // uint
#define RRC_PC_OFFSET_REFRESH_PHASE 124 // uint: frame_index mod refresh_period, formed in 64-bit on the CPU
#define RRC_PC_SIZE 128

#endif  // RRC_KERNEL_INTERFACE_H
