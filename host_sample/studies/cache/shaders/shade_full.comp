#version 450
// Shading every pixel: the frame without the cache, and the target the cached
// frame's error is measured against.
#extension GL_GOOGLE_include_directive : require
#include "perlin.glsl"
layout(local_size_x = 128, local_size_y = 1) in;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D shaded;
layout(push_constant) uniform Push { uvec2 size; } pc;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= int(pc.size.x) || px.y >= int(pc.size.y)) return;
    imageStore(shaded, px, perlin_shade(px));
}
