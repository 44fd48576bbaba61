#version 450
// The miss shader: dispatched indirectly on rrc's quad list
// (include/rrc/rrc_values.h layout; docs/guide/integration.md "The shading cache"),
// one invocation a listed 2x2 quad, every pixel of it inside the frame.
// Counts the quads it shaded, so the host can check it ran on exactly the list.
#extension GL_GOOGLE_include_directive : require
#include "rrc/rrc_values.h"
#include "perlin.glsl"
layout(local_size_x = RRC_QUADS_PER_GROUP, local_size_y = 1) in;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D shaded;
layout(std430, set = 0, binding = 3) readonly buffer List { uint words[]; } list;
layout(std430, set = 0, binding = 4) buffer Counter { uint quads; } counter;
layout(push_constant) uniform Push { uvec2 size; } pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= list.words[RRC_QUAD_LIST_COUNT]) return;
    uint q = list.words[RRC_QUAD_LIST_FIRST_QUAD + i];
    ivec2 p0 = 2 * ivec2(q & 0xFFFFu, q >> 16);
    for (int k = 0; k < 4; ++k) {
        ivec2 p = p0 + ivec2(k & 1, k >> 1);
        if (p.x < int(pc.size.x) && p.y < int(pc.size.y)) imageStore(shaded, p, perlin_shade(p));
    }
    atomicAdd(counter.quads, 1u);
}
