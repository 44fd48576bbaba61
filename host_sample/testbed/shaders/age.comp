#version 450
// The host's copy of the cache age, for the age heat map: the interop API
// returns no age image, so the sample follows rrc's rule from its mask
// (docs/CONVENTIONS.md): background 0, miss 1, hit min(n_prev + 1, cap)
// with n_prev fetched nearest at the pixel's previous position (from the
// G-buffer's previous clip position).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(local_size_x = 128, local_size_y = 1) in;

layout(set = 0, binding = 1) uniform sampler2D g_prev_clip;
layout(set = 0, binding = 2, r8ui) uniform readonly uimage2D rrc_mask;
layout(set = 0, binding = 3, r16ui) uniform readonly uimage2D age_prev;
layout(set = 0, binding = 4, r16ui) uniform writeonly uimage2D age_out;
layout(push_constant) uniform Push { uint cap; } pc;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(u.frame.zw);
    if (px.x >= size.x || px.y >= size.y) return;
    uint mask = imageLoad(rrc_mask, px).r;
    uint age = 1u;
    if ((mask & RRC_MASK_BACKGROUND) != 0u) {
        age = 0u;
    } else if ((mask & RRC_MASK_HIT) != 0u) {
        vec4 c = texelFetch(g_prev_clip, px, 0);
        vec2 uv = (c.xy / c.w + 1.0) * 0.5;
        ivec2 q = clamp(ivec2(floor(uv * vec2(size))), ivec2(0), size - 1);
        age = min(imageLoad(age_prev, q).r + 1u, pc.cap);
    }
    imageStore(age_out, px, uvec4(age));
}
