#version 450
// The fused kernel: reverse reprojection, the epsilon-depth hit test and the
// lambda recursive filter for up to RRC_MAX_CHANNELS channels, one pass.
// Written for lavapipe's costs (SPEC §8): plain storage-image loads with
// format qualifiers, one set of bilinear weights shared by the depth test and
// every history fetch, wide 128x1 workgroups, no shared memory, straight-line
// code where the specialization constants have folded the branches.
#extension GL_GOOGLE_include_directive : require

#define RRC_MAX_CHANNELS 4
#define RRC_MASK_HIT 1u
#define RRC_MASK_BACKGROUND 4u
#define RRC_MASK_INVALID_SAMPLE 8u
#define RRC_MASK_INVALID_GEOMETRY 16u

layout(local_size_x_id = 100, local_size_y_id = 101) in;

#include "rrc_reproject.glsl"
#include "rrc_filter.glsl"

layout(constant_id = 4) const uint CH_COUNT = 1u;

// Per-slot specialization constants, id 16 + 4*k + slot for property k
// (plugin/kernel_config.h).
layout(constant_id = 16) const uint CH0_COMPONENTS = 1u;
layout(constant_id = 17) const uint CH1_COMPONENTS = 1u;
layout(constant_id = 18) const uint CH2_COMPONENTS = 1u;
layout(constant_id = 19) const uint CH3_COMPONENTS = 1u;
layout(constant_id = 20) const bool CH0_FP16 = true;
layout(constant_id = 21) const bool CH1_FP16 = true;
layout(constant_id = 22) const bool CH2_FP16 = true;
layout(constant_id = 23) const bool CH3_FP16 = true;
layout(constant_id = 24) const uint CH0_BLEND = 0u;
layout(constant_id = 25) const uint CH1_BLEND = 0u;
layout(constant_id = 26) const uint CH2_BLEND = 0u;
layout(constant_id = 27) const uint CH3_BLEND = 0u;
layout(constant_id = 28) const uint CH0_FILTER = 0u;
layout(constant_id = 29) const uint CH1_FILTER = 0u;
layout(constant_id = 30) const uint CH2_FILTER = 0u;
layout(constant_id = 31) const uint CH3_FILTER = 0u;
layout(constant_id = 32) const bool CH0_CONFIDENCE = false;
layout(constant_id = 33) const bool CH1_CONFIDENCE = false;
layout(constant_id = 34) const bool CH2_CONFIDENCE = false;
layout(constant_id = 35) const bool CH3_CONFIDENCE = false;
layout(constant_id = 36) const float CH0_LAMBDA = 0.6;
layout(constant_id = 37) const float CH1_LAMBDA = 0.6;
layout(constant_id = 38) const float CH2_LAMBDA = 0.6;
layout(constant_id = 39) const float CH3_LAMBDA = 0.6;
layout(constant_id = 40) const uint CH0_AGE_CAP = 255u;
layout(constant_id = 41) const uint CH1_AGE_CAP = 255u;
layout(constant_id = 42) const uint CH2_AGE_CAP = 255u;
layout(constant_id = 43) const uint CH3_AGE_CAP = 255u;
// Slot selectors: called with a literal slot, they fold to one constant.
#define RRC_SLOT_SELECT(T, name) \
    T ch_##name(int c) { return c == 0 ? CH0_##name : c == 1 ? CH1_##name : c == 2 ? CH2_##name : CH3_##name; }
RRC_SLOT_SELECT(uint, COMPONENTS)
RRC_SLOT_SELECT(bool, FP16)
RRC_SLOT_SELECT(uint, BLEND)
RRC_SLOT_SELECT(uint, FILTER)
RRC_SLOT_SELECT(bool, CONFIDENCE)
RRC_SLOT_SELECT(float, LAMBDA)
RRC_SLOT_SELECT(uint, AGE_CAP)

layout(set = 0, binding = 5, r8ui) uniform writeonly uimage2D u_mask;

// Per-channel images, arrays indexed by slot.  Slots and format variants a
// configuration does not use are bound to 1x1 placeholders and never touched.
layout(set = 0, binding = 10, r32f) uniform readonly image2D u_sample1[RRC_MAX_CHANNELS];
layout(set = 0, binding = 11, rgba32f) uniform readonly image2D u_sample4[RRC_MAX_CHANNELS];
layout(set = 0, binding = 12, r32f) uniform readonly image2D u_confidence[RRC_MAX_CHANNELS];
layout(set = 0, binding = 13, r16f) uniform readonly image2D u_hist_r16f[RRC_MAX_CHANNELS];
layout(set = 0, binding = 14, rgba16f) uniform readonly image2D u_hist_rgba16f[RRC_MAX_CHANNELS];
layout(set = 0, binding = 15, r32f) uniform readonly image2D u_hist_r32f[RRC_MAX_CHANNELS];
layout(set = 0, binding = 16, rgba32f) uniform readonly image2D u_hist_rgba32f[RRC_MAX_CHANNELS];
layout(set = 0, binding = 17, r16ui) uniform readonly uimage2D u_age[RRC_MAX_CHANNELS];
layout(set = 0, binding = 18, r32f) uniform readonly image2D u_weight[RRC_MAX_CHANNELS];
layout(set = 0, binding = 19) uniform writeonly image2D u_hist_out[RRC_MAX_CHANNELS];  // any float format
layout(set = 0, binding = 20, r16ui) uniform writeonly uimage2D u_age_out[RRC_MAX_CHANNELS];
layout(set = 0, binding = 21, r32f) uniform writeonly image2D u_weight_out[RRC_MAX_CHANNELS];
layout(set = 0, binding = 22) uniform sampler2D s_samples[RRC_MAX_CHANNELS];     // INTEROP
layout(set = 0, binding = 23) uniform sampler2D s_confidence[RRC_MAX_CHANNELS];  // INTEROP
layout(set = 0, binding = 24) uniform writeonly image2D u_host_out[RRC_MAX_CHANNELS];  // INTEROP: any float format

void main() {
    ivec2 size = rrc_size();
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= size.x || px.y >= size.y) return;  // the dispatch rounds up

    RrcGeometry g = rrc_reproject(px, size);
    uint mask = (g.hit ? RRC_MASK_HIT : 0u) | (g.background ? RRC_MASK_BACKGROUND : 0u) |
                (g.invalid ? RRC_MASK_INVALID_GEOMETRY : 0u);

#define RRC_CH 0
#include "rrc_channel.glsl"
#undef RRC_CH
#define RRC_CH 1
#include "rrc_channel.glsl"
#undef RRC_CH
#define RRC_CH 2
#include "rrc_channel.glsl"
#undef RRC_CH
#define RRC_CH 3
#include "rrc_channel.glsl"
#undef RRC_CH

    imageStore(u_mask, px, uvec4(mask));
}
