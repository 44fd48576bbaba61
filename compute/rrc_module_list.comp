// The shading cache's list pass (docs/design/frame-plan.md):
// classify's quad list from its mask.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "rrc_values.glsl"  // RRC_MAX_CHANNELS, RRC_MASK_*, spec ids, bindings

layout(local_size_x_id = RRC_SPEC_GROUP_SIZE_X, local_size_y_id = RRC_SPEC_GROUP_SIZE_Y) in;

// This pass's bindings, exactly (rrc_module_bindings.h; the library's layout is made from the same list).
#include "rrc_bindings.glsl"
RRC_MODULE_LIST_BINDINGS(RRC_DECLARE)

#include "rrc_mask.glsl"
#include "rrc_list.glsl"
RRC_QUAD_LIST_APPENDER  // rrc_list_quad

// LIST: one invocation a 2x2 quad, after CLASSIFY wrote the mask (a pass of
// its own: one invocation a quad would run the reprojection of four pixels
// in a row, about twice the time of one a pixel on lavapipe).  The quad is
// listed when one of its pixels inside the frame is not a HIT.
void rrc_list_quads() {
    ivec2 size = imageSize(u_mask);
    ivec2 quads = (size + 1) / 2;
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    ivec2 q = min(id, quads - 1);
    bool listed = false;
    for (int k = 0; k < 4; ++k) {
        ivec2 px = 2 * q + ivec2(k & 1, k >> 1);
        bool inside = all(lessThan(px, size));
        uint mask = rrc_classified(min(px, size - 1));
        listed = listed || (inside && (mask & RRC_MASK_HIT) == 0u);
    }
    if (listed && all(lessThan(id, quads))) rrc_list_quad(q);
}

void main() { rrc_list_quads(); }
