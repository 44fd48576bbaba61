// Every descriptor binding's GLSL declaration (set 0, the numbers of
// rrc_kernel_interface.h), one macro each: a pass declares exactly the
// bindings of its list in rrc_module_bindings.h, the list the library makes its
// descriptor-set layout from, by expanding it with RRC_DECLARE before it
// includes the function libraries that use them:
//     RRC_MODULE_LIST_BINDINGS(RRC_DECLARE)
// Per-channel bindings are arrays of RRC_MAX_CHANNELS, indexed by slot
// (rrc_channel_slots.glsl).  Every imageLoad needs a format qualifier
// (lavapipe); write-only images of any float format are declared without one.
#ifndef RRC_BINDINGS_GLSL
#define RRC_BINDINGS_GLSL

#include "rrc_values.glsl"  // RRC_MAX_CHANNELS, RRC_BINDING_*, RRC_STAT_COUNT
#include "rrc_module_bindings.h"

#define RRC_DECLARE(name) RRC_DECLARE_##name

// A channel slot's parameters: one member a PARAM row of
// rrc_channel_options.def, in row order (the library's mirror,
// plugin/accumulate_pipeline.h KernelChannelParams, comes from the same rows).
#define RRC_GLSL_TYPE_float float
#define RRC_GLSL_TYPE_uint32_t uint
#define RRC_PARAM_NONE(ctype, member)
#define RRC_PARAM_PARAM(ctype, member) RRC_GLSL_TYPE_##ctype member;
struct RrcChannelParams {
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, bit, width, feature, version, anchor) \
    RRC_PARAM_##param(ctype, member)
#include "rrc_channel_options.def"
#undef RRC_CHANNEL_OPTION
};
#undef RRC_PARAM_PARAM
#undef RRC_PARAM_NONE

#define RRC_DECLARE_DEPTH layout(set = 0, binding = RRC_BINDING_DEPTH, r32f) uniform readonly image2D u_depth;
#define RRC_DECLARE_PREV_DEPTH layout(set = 0, binding = RRC_BINDING_PREV_DEPTH, r32f) uniform readonly image2D u_prev_depth;
// REPROJ: PREV_CLIP, MOTION (.xy), MOTION_DEPTH
#define RRC_DECLARE_REPROJ layout(set = 0, binding = RRC_BINDING_REPROJ, rgba32f) uniform readonly image2D u_reproj;
// PREV_OBJECT_ID: the previous frame's ids
#define RRC_DECLARE_PREV_OBJECT_ID layout(set = 0, binding = RRC_BINDING_PREV_OBJECT_ID, r32ui) uniform readonly uimage2D u_prev_object_id;
#define RRC_DECLARE_NOCACHE layout(set = 0, binding = RRC_BINDING_NOCACHE, r8ui) uniform readonly uimage2D u_nocache;
// MASK: written by the per-pixel passes, read where classify wrote it (MASK_IN_PLACE), the host's for copy-out
#define RRC_DECLARE_MASK layout(set = 0, binding = RRC_BINDING_MASK, r8ui) uniform uimage2D u_mask;
// HOST_DEPTH: INTEROP: the host's depth
#define RRC_DECLARE_HOST_DEPTH layout(set = 0, binding = RRC_BINDING_HOST_DEPTH) uniform sampler2D s_depth;
// HOST_REPROJ: INTEROP: the host's reprojection data
#define RRC_DECLARE_HOST_REPROJ layout(set = 0, binding = RRC_BINDING_HOST_REPROJ) uniform sampler2D s_reproj;
// HOST_NOCACHE: INTEROP: the host's do-not-cache mask
#define RRC_DECLARE_HOST_NOCACHE layout(set = 0, binding = RRC_BINDING_HOST_NOCACHE) uniform usampler2D s_nocache;
// DEPTH_OUT: INTEROP: next frame's previous depth
#define RRC_DECLARE_DEPTH_OUT layout(set = 0, binding = RRC_BINDING_DEPTH_OUT, r32f) uniform writeonly image2D u_depth_out;
#define RRC_DECLARE_SAMPLE1 layout(set = 0, binding = RRC_BINDING_SAMPLE1, r32f) uniform readonly image2D u_sample1[RRC_MAX_CHANNELS];
#define RRC_DECLARE_SAMPLE4 layout(set = 0, binding = RRC_BINDING_SAMPLE4, rgba32f) uniform readonly image2D u_sample4[RRC_MAX_CHANNELS];
#define RRC_DECLARE_CONFIDENCE layout(set = 0, binding = RRC_BINDING_CONFIDENCE, r32f) uniform readonly image2D u_confidence[RRC_MAX_CHANNELS];
#define RRC_DECLARE_HIST_PACKED layout(set = 0, binding = RRC_BINDING_HIST_PACKED, r32ui) uniform readonly uimage2D u_hist_packed[RRC_MAX_CHANNELS];
#define RRC_DECLARE_HIST_RGBA16F layout(set = 0, binding = RRC_BINDING_HIST_RGBA16F, rgba16f) uniform readonly image2D u_hist_rgba16f[RRC_MAX_CHANNELS];
#define RRC_DECLARE_HIST_R32F layout(set = 0, binding = RRC_BINDING_HIST_R32F, r32f) uniform readonly image2D u_hist_r32f[RRC_MAX_CHANNELS];
#define RRC_DECLARE_HIST_RGBA32F layout(set = 0, binding = RRC_BINDING_HIST_RGBA32F, rgba32f) uniform readonly image2D u_hist_rgba32f[RRC_MAX_CHANNELS];
#define RRC_DECLARE_AGE layout(set = 0, binding = RRC_BINDING_AGE, r16ui) uniform readonly uimage2D u_age[RRC_MAX_CHANNELS];
#define RRC_DECLARE_WEIGHT layout(set = 0, binding = RRC_BINDING_WEIGHT, r32f) uniform readonly image2D u_weight[RRC_MAX_CHANNELS];
// HIST_OUT: any float format
#define RRC_DECLARE_HIST_OUT layout(set = 0, binding = RRC_BINDING_HIST_OUT) uniform writeonly image2D u_hist_out[RRC_MAX_CHANNELS];
// AGE_OUT: R16_UINT ages, or for packed channels their R32_UINT value|age words (so declared without a format)
#define RRC_DECLARE_AGE_OUT layout(set = 0, binding = RRC_BINDING_AGE_OUT) uniform writeonly uimage2D u_age_out[RRC_MAX_CHANNELS];
// WEIGHT_OUT: R32F weights (confidence), or a gated channel's R32G32F (beta, varsigma) (so declared without a format)
#define RRC_DECLARE_WEIGHT_OUT layout(set = 0, binding = RRC_BINDING_WEIGHT_OUT) uniform writeonly image2D u_weight_out[RRC_MAX_CHANNELS];
// HOST_SAMPLES: INTEROP
#define RRC_DECLARE_HOST_SAMPLES layout(set = 0, binding = RRC_BINDING_HOST_SAMPLES) uniform sampler2D s_samples[RRC_MAX_CHANNELS];
// HOST_CONFIDENCE: INTEROP
#define RRC_DECLARE_HOST_CONFIDENCE layout(set = 0, binding = RRC_BINDING_HOST_CONFIDENCE) uniform sampler2D s_confidence[RRC_MAX_CHANNELS];
// HOST_OUT: INTEROP: any float format
#define RRC_DECLARE_HOST_OUT layout(set = 0, binding = RRC_BINDING_HOST_OUT) uniform writeonly image2D u_host_out[RRC_MAX_CHANNELS];
// HOST_AGE_OUT: INTEROP, optional
#define RRC_DECLARE_HOST_AGE_OUT layout(set = 0, binding = RRC_BINDING_HOST_AGE_OUT, r16ui) uniform writeonly uimage2D u_host_age_out[RRC_MAX_CHANNELS];
// OBJECT_ID: INTEROP: next frame's previous ids
#define RRC_DECLARE_OBJECT_ID layout(set = 0, binding = RRC_BINDING_OBJECT_ID, r32ui) uniform writeonly uimage2D u_object_id_out;
// HOST_OBJECT_ID: this frame's ids
#define RRC_DECLARE_HOST_OBJECT_ID layout(set = 0, binding = RRC_BINDING_HOST_OBJECT_ID) uniform usampler2D s_object_id;
// CLASSIFIED: classify's mask through a sampler (the storage images are at lavapipe's 64 a stage)
#define RRC_DECLARE_CLASSIFIED layout(set = 0, binding = RRC_BINDING_CLASSIFIED) uniform usampler2D s_classified;
// FALLBACK: the host's fallback estimate: FILL's prior, and a residual's base b (the per-pixel passes and FILL)
#define RRC_DECLARE_FALLBACK layout(set = 0, binding = RRC_BINDING_FALLBACK) uniform sampler2D s_fallback[RRC_MAX_CHANNELS];
// GATE: a gated channel's previous state, fp16 (beta, sqrt(varsigma)) packed in one word a
// texel (an R32_UINT view of its R16G16_SFLOAT image; docs/CONVENTIONS.md, "The deviation gate")
#define RRC_DECLARE_GATE layout(set = 0, binding = RRC_BINDING_GATE) uniform usampler2D s_gate[RRC_MAX_CHANNELS];
// STATS: rrc_vulkan_frame_stats (include/rrc/rrc_vulkan.h), cleared by the library before the dispatch;
// with COUNT_IO, rrc_vulkan_io_counts after it (rrc_io.glsl): the bound range says how many words
#define RRC_DECLARE_STATS layout(std430, set = 0, binding = RRC_BINDING_STATS) buffer Stats { uint counters[]; } u_stats;
// QUADS: classify's quad list (rrc_list.glsl)
#define RRC_DECLARE_QUADS layout(std430, set = 0, binding = RRC_BINDING_QUADS) buffer Quads { uint words[]; } u_quads;
// FILL_LIST: the fill list (rrc_list.glsl)
#define RRC_DECLARE_FILL_LIST layout(std430, set = 0, binding = RRC_BINDING_FILL_LIST) buffer FillList { uint words[]; } u_fill;
// VIEW: the view lobe's camera (rrc_kernel_interface.h), read only
// CHANNEL_PARAMS: each slot's parameters (written once, at creation)
#define RRC_DECLARE_CHANNEL_PARAMS layout(std140, set = 0, binding = RRC_BINDING_CHANNEL_PARAMS) uniform ChannelParams { RrcChannelParams slot[RRC_MAX_CHANNELS]; } u_params;
#define RRC_DECLARE_VIEW layout(std430, set = 0, binding = RRC_BINDING_VIEW) readonly buffer View { mat4 Q; vec4 d; } u_view;

#endif
