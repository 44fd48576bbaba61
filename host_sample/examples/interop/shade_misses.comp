#version 450
// The miss shader (docs/guide/integration.md, "The frame, interop"), dispatched indirectly: invocation n shades rrc's listed quad n.
#extension GL_GOOGLE_include_directive : require
#include "rrc/rrc_values.h"
layout(local_size_x = RRC_QUADS_PER_GROUP) in;
layout(std430, binding = 0) readonly buffer QuadList { uint entries[]; } quad_list;
layout(binding = 1, r32f) uniform writeonly image2D shaded;
layout(push_constant) uniform Shading { float value; } shading;
void main() {
    const uint entry = gl_GlobalInvocationID.x;
    if (entry >= quad_list.entries[RRC_QUAD_LIST_COUNT]) return;
    const uint quad = quad_list.entries[RRC_QUAD_LIST_FIRST_QUAD + entry];
    for (int k = 0; k < 4; ++k) {
        const ivec2 pixel = ivec2(quad & 0xFFFFu, quad >> 16) * 2 + ivec2(k % 2, k / 2);
        if (all(lessThan(pixel, imageSize(shaded)))) imageStore(shaded, pixel, vec4(shading.value));  // odd sizes
    }
}
