// The spatial fill pass (docs/CONVENTIONS.md, "The spatial fill"): the
// displayed value of every channel with a fill, at the pixels of the fill list.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "rrc_values.glsl"  // RRC_MAX_CHANNELS, RRC_MASK_*, spec ids, bindings

layout(local_size_x_id = RRC_SPEC_GROUP_SIZE_X, local_size_y_id = RRC_SPEC_GROUP_SIZE_Y) in;

// This pass's bindings, exactly (rrc_module_bindings.h; the library's layout is made from the same list).
#include "rrc_bindings.glsl"
RRC_MODULE_FILL_BINDINGS(RRC_DECLARE)
#include "rrc_io_flush.glsl"  // RRC_LOAD, rrc_io_store, rrc_io_flush: the counted image operations

#include "rrc_depth.glsl"
#include "rrc_filter.glsl"  // rrc_plus_base (a residual's displayed value)
#include "rrc_channel_slots.glsl"
#include "rrc_list.glsl"

// The spatial fill's depth test |delta_q - delta_p| <= tau delta_p on the
// proxy delta (docs/CONVENTIONS.md, "The spatial fill": d, 1/(1 - z), 1/z),
// multiplied out so that no tap divides: STANDARD |z_q - z_p| <= tau (1 - z_q),
// REVERSED |z_p - z_q| <= tau z_q (both denominators positive off background).
bool rrc_fill_similar(float d_q, float d_p, float tau) {
    if (DEPTH_MODE == RRC_DEPTH_MODE_STANDARD) return abs(d_q - d_p) <= tau * (1.0 - d_q);
    if (DEPTH_MODE == RRC_DEPTH_MODE_REVERSED) return abs(d_p - d_q) <= tau * d_q;
    return abs(d_q - d_p) <= tau * d_p;
}

// The module's RRC_SLOTS slots' fills, rrc_fill_channel_0 .. (rrc_channel_slots.glsl);
// slots past them are not compiled.
#define RRC_CH 0
#include "rrc_fill_channel.glsl"
#undef RRC_CH
#if RRC_SLOTS > 1
#define RRC_CH 1
#include "rrc_fill_channel.glsl"
#undef RRC_CH
#endif
#if RRC_SLOTS > 2
#define RRC_CH 2
#include "rrc_fill_channel.glsl"
#undef RRC_CH
#endif
#if RRC_SLOTS > 3
#define RRC_CH 3
#include "rrc_fill_channel.glsl"
#undef RRC_CH
#endif

// FILL: one invocation a listed pixel (the fill list, indirect: the
// sub-lists' groups one after another, rrc_kernel_interface.h), after the
// frame's channels, bound as the next frame would be (its history inputs are
// this frame's results, its previous depth this frame's depth): the
// displayed value of every channel with a fill, into u_host_out
// (docs/CONVENTIONS.md, "The spatial fill").  Every other pixel's displayed
// value is its history value, which the frame's pass wrote there.
void rrc_fill() {
    ivec2 size = imageSize(u_prev_depth);
    // The group's sub-list and its group there: the sub-lists' groups in order.
    uint list = 0u, group = gl_WorkGroupID.x, count;
    for (;; ++list) {
        count = u_fill.words[RRC_FILL_LIST_COUNTS + list * RRC_FILL_LIST_COUNT_STRIDE];
        uint groups = (count + RRC_FILL_LIST_PER_GROUP - 1u) / RRC_FILL_LIST_PER_GROUP;
        if (group < groups || list + 1u == RRC_FILL_LISTS) break;
        group -= groups;
    }
    uint slot = group * RRC_FILL_LIST_PER_GROUP + gl_LocalInvocationID.x;
    rrc_store = slot < count;  // no early return (rrc_reproject.glsl says why)
    uint first = RRC_FILL_LIST_FIRST + list * RRC_FILL_LIST_CAPACITY(uint(size.x), uint(size.y));
    uint word = u_fill.words[first + min(slot, max(count, 1u) - 1u)];
    ivec2 px = min(ivec2(word & 0xFFFFu, word >> 16), size - 1);
    float d_p = RRC_LOAD(1u, 4u, imageLoad(u_prev_depth, px).r);
    bool fill_here = !rrc_is_background(d_p);
    bool valid_p = !rrc_is_invalid_depth(d_p);  // an invalid depth takes no neighbour, only the fallback

    rrc_fill_channel_0(size, px, rrc_store, fill_here, valid_p, d_p);
#if RRC_SLOTS > 1
    rrc_fill_channel_1(size, px, rrc_store, fill_here, valid_p, d_p);
#endif
#if RRC_SLOTS > 2
    rrc_fill_channel_2(size, px, rrc_store, fill_here, valid_p, d_p);
#endif
#if RRC_SLOTS > 3
    rrc_fill_channel_3(size, px, rrc_store, fill_here, valid_p, d_p);
#endif
    rrc_io_flush(rrc_store);
}

void main() { rrc_fill(); }
