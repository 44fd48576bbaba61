#version 450
// Signal 1, amortized PCF (the paper's Section 7.3): k shadow-map tests per
// pixel on a Poisson disk rotated by a random angle per pixel and frame.
// Reference mode: samples/k stratified rotations of the same pattern, the
// value the recursive filter converges to.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(local_size_x = 128, local_size_y = 1) in;

layout(set = 0, binding = 1) uniform sampler2D g_position;
layout(set = 0, binding = 2) uniform sampler2D g_normal_material;
layout(set = 0, binding = 3) uniform sampler2D sun_map;
layout(set = 0, binding = 4, r32f) uniform writeonly image2D o_signal;
layout(push_constant) uniform Push { uint samples; uint reference; } pc;  // reference: 0 per frame, 1 reference, 2 brute force

float sun_test(vec2 texel, float z, int size) {
    ivec2 c = clamp(ivec2(floor(texel)), ivec2(0), ivec2(size - 1));
    return z <= texelFetch(sun_map, c, 0).r ? 1.0 : 0.0;
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= int(u.frame.z) || px.y >= int(u.frame.w)) return;
    vec4 nm = texelFetch(g_normal_material, px, 0);
    if (material_of(nm) == MAT_BACKGROUND) {
        imageStore(o_signal, px, vec4(1.0));
        return;
    }
    vec3 p = texelFetch(g_position, px, 0).xyz + nm.xyz * u.sun_dir.w;  // normal offset
    vec4 lc = u.sun_vp * vec4(p, 1.0);
    int size = int(u.lamp_colour.w);
    vec2 texel = (lc.xy * 0.5 + 0.5) * float(size);
    float z = lc.z - u.ambient.w / 79.0;  // ortho depth spans 79 world units
    float radius = u.sun_colour.w;
    uint k = u.frame.y;
    uint rotations = pc.reference != 0u ? max(pc.samples / k, 1u) : 1u;
    // Random streams: 1 per-frame signal, 0x5eed + reference for the reference (1) and the brute force (2).
    float offset = rnd(uint(px.x), uint(px.y), u.frame.x, pc.reference != 0u ? 0x5eedu + pc.reference : 1u);
    float lit = 0.0;
    for (uint r = 0u; r < rotations; ++r) {
        float a = 2.0 * PI * (float(r) + offset) / float(rotations);
        mat2 rot = mat2(cos(a), sin(a), -sin(a), cos(a));
        for (uint i = 0u; i < k; ++i) lit += sun_test(texel + radius * (rot * u.poisson[i].xy), z, size);
    }
    imageStore(o_signal, px, vec4(lit / float(rotations * k)));
}
