// The library's two lists, one layout (include/rrc/rrc_values.h,
// rrc_kernel_interface.h): a count, a VkDispatchIndirectCommand over groups
// of `per_group` entries, the entries.  Classify's quad list (u_quads): the
// list pass appends the quads with a pixel that is not a HIT, RESOLVE_LISTED
// runs over them (docs/design/frame-plan.md).  The fill list
// (u_fill; docs/CONVENTIONS.md, "The spatial fill"): the passes that write
// channels append the pixels younger than a fill age to its sub-lists, the
// fill pass runs over them.  GLSL passes no buffer to a function, and a pass declares only
// the list it uses (rrc_module_bindings.h): so a pass defines its own appender.
#ifndef RRC_LIST_GLSL
#define RRC_LIST_GLSL

#include "rrc_values.glsl"  // RRC_QUAD_LIST_*, RRC_QUADS_PER_GROUP, RRC_FILL_LIST_*

// RRC_LIST_APPENDER(name, list, ...) defines `void name(ivec2 xy)`, which appends
// xy as x | y << 16 to `list` (a buffer's words).  The dispatch's x covers the
// largest slot taken: slot / per_group + 1 = ceil(count / per_group).  Every slot
// below the count is taken, so only the first slot of each group needs to raise
// it: one atomicMax a group, not one an entry.  A pass defines the appender of the
// list it declares: RRC_QUAD_LIST_APPENDER, RRC_FILL_LIST_APPENDER.
#define RRC_LIST_APPENDER(name, words, count_at, dispatch_at, first_at, per_group)                  \
    void name(ivec2 xy) {                                                                          \
        uint slot = atomicAdd(words[count_at], 1u);                                                \
        words[first_at + slot] = uint(xy.x) | (uint(xy.y) << 16);                                  \
        if (slot % (per_group) == 0u) atomicMax(words[dispatch_at], slot / (per_group) + 1u);      \
    }
// rrc_list_quad(q): quad q into classify's quad list.
#define RRC_QUAD_LIST_APPENDER \
    RRC_LIST_APPENDER(rrc_list_quad, u_quads.words, RRC_QUAD_LIST_COUNT, RRC_QUAD_LIST_DISPATCH, RRC_QUAD_LIST_FIRST_QUAD, RRC_QUADS_PER_GROUP)
// rrc_list_fill(px, size): pixel px of a frame of `size` into its sub-list of
// the fill list (rrc_kernel_interface.h).  The dispatch's x counts every
// sub-list's groups: the slot that starts a group adds one.
#define RRC_FILL_LIST_APPENDER                                                                          \
    void rrc_list_fill(ivec2 xy, ivec2 size) {                                                          \
        uint list = uint(xy.y) / RRC_FILL_LIST_BAND(uint(size.y));                                      \
        uint slot = atomicAdd(u_fill.words[RRC_FILL_LIST_COUNTS + list * RRC_FILL_LIST_COUNT_STRIDE], 1u); \
        u_fill.words[RRC_FILL_LIST_FIRST + list * RRC_FILL_LIST_CAPACITY(uint(size.x), uint(size.y)) + slot] = \
            uint(xy.x) | (uint(xy.y) << 16);                                                            \
        if (slot % RRC_FILL_LIST_PER_GROUP == 0u) atomicAdd(u_fill.words[RRC_FILL_LIST_DISPATCH], 1u);  \
    }

#endif
