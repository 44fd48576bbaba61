// The fill list (rrc_kernel_interface.h; docs/CONVENTIONS.md, "The spatial
// fill"): the passes that write channels append to it, the fill pass runs
// over it.
#ifndef RRC_FILL_LIST_GLSL
#define RRC_FILL_LIST_GLSL

#include "rrc_values.glsl"  // bindings, RRC_FILL_LIST_*

// Appends px to the fill list; the indirect dispatch's x is the largest
// group an entry falls in, + 1: raised only by the first entry of each group.
void rrc_list_fill(ivec2 px) {
    uint slot = atomicAdd(u_fill.words[RRC_FILL_LIST_COUNT], 1u);
    u_fill.words[RRC_FILL_LIST_FIRST + slot] = uint(px.x) | (uint(px.y) << 16);
    if (slot % RRC_FILL_LIST_PER_GROUP == 0u) atomicMax(u_fill.words[RRC_FILL_LIST_DISPATCH], slot / RRC_FILL_LIST_PER_GROUP + 1u);
}

#endif
