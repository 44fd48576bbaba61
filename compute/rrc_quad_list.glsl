// Classify's quad list (include/rrc/rrc_values.h layout): count,
// VkDispatchIndirectCommand, quads.  The list pass appends to it,
// RESOLVE_LISTED runs over it (docs/PERFORMANCE.md, "The frame plan").
#ifndef RRC_QUAD_LIST_GLSL
#define RRC_QUAD_LIST_GLSL

#include "rrc_values.glsl"  // bindings, RRC_QUAD_LIST_*

// Appends quad q to classify's list and keeps the indirect dispatch's x
// covering it: the largest slot / RRC_QUADS_PER_GROUP + 1 = ceil(count / per
// group).  Every slot below the count is taken, so only the first slot of
// each group needs to raise it: one atomicMax a group, not one a quad.
void rrc_list_quad(ivec2 q) {
    uint slot = atomicAdd(u_quads.words[RRC_QUAD_LIST_COUNT], 1u);
    u_quads.words[RRC_QUAD_LIST_FIRST_QUAD + slot] = uint(q.x) | (uint(q.y) << 16);
    if (slot % RRC_QUADS_PER_GROUP == 0u) atomicMax(u_quads.words[RRC_QUAD_LIST_DISPATCH], slot / RRC_QUADS_PER_GROUP + 1u);
}

#endif
