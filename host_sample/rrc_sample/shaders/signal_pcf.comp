#version 450
// Signal 1, amortized PCF (the paper's Section 7.3).  The target is the
// disk's area mean of the nearest-texel shadow test (disk of radius R
// texels around the receiver's map position): every tap's marginal is
// uniform over that disk, so each frame is an unbiased estimate of it.
//   pattern 0 (default): k points stratified in radius, (j + 1/2)/k, and
//     spread in angle by the golden ratio, shifted by a random toroidal
//     offset per pixel and frame (Cranley-Patterson), mapped to the disk
//     with r = R sqrt(u), phi = 2 pi v;
//   pattern 1: the paper's fixed k-point Poisson disk rotated by a random
//     angle per pixel and frame (biased for the target: rotation keeps each
//     tap on its own radius).
// reference 1: the target itself, exactly (disk_area.glsl); 2: brute force,
// `samples` taps of the pattern (pattern 1: samples/k stratified rotations).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "disk_area.glsl"
layout(local_size_x = 128, local_size_y = 1) in;

layout(set = 0, binding = 1) uniform sampler2D g_position;
layout(set = 0, binding = 2) uniform sampler2D g_normal_material;
layout(set = 0, binding = 3) uniform sampler2D sun_map;
layout(set = 0, binding = 4, r32f) uniform writeonly image2D o_signal;
layout(push_constant) uniform Push {
    uint samples;    // brute force: taps
    uint reference;  // 0 per frame, 1 the exact target, 2 brute force
    uint seed;       // the ensemble member: moves every random stream
    uint pattern;    // 0 uniform disk, 1 rotated Poisson
} pc;

float sun_test(ivec2 c, float z, int size) {
    return z <= texelFetch(sun_map, clamp(c, ivec2(0), ivec2(size - 1)), 0).r ? 1.0 : 0.0;
}
float sun_test(vec2 texel, float z, int size) { return sun_test(ivec2(floor(texel)), z, size); }

// The exact mean of the test over the disk: each texel weighted by the area
// of the disk inside it (texel i covers [i, i+1); clamped fetches at the
// map's border, as the taps).
float disk_mean(vec2 centre, float radius, float z, int size) {
    ivec2 lo = ivec2(floor(centre - radius)), hi = ivec2(floor(centre + radius));
    float lit = 0.0;
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
            vec2 a = vec2(x, y) - centre;
            float w = disk_rect_area(radius, a.x, a.x + 1.0, a.y, a.y + 1.0);
            if (w > 0.0) lit += w * sun_test(ivec2(x, y), z, size);
        }
    return lit / (PI * radius * radius);
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
    if (pc.reference == 1u) {
        imageStore(o_signal, px, vec4(disk_mean(texel, radius, z, size)));
        return;
    }
    uint k = u.frame.y;
    uint n = pc.reference != 0u ? pc.samples : k;
    // Random streams: 1 per-frame signal, 0x5eed + 2 brute force; the seed moves them all.
    uint stream = (pc.reference != 0u ? 0x5eedu + pc.reference : 1u) + 0x10000u * pc.seed;
    float lit = 0.0;
    if (pc.pattern == 1u) {
        uint rotations = max(n / k, 1u);
        float offset = rnd(uint(px.x), uint(px.y), u.frame.x, stream);
        for (uint r = 0u; r < rotations; ++r) {
            float a = 2.0 * PI * (float(r) + offset) / float(rotations);
            mat2 rot = mat2(cos(a), sin(a), -sin(a), cos(a));
            for (uint i = 0u; i < k; ++i) lit += sun_test(texel + radius * (rot * u.poisson[i].xy), z, size);
        }
        n = rotations * k;
    } else {
        vec2 shift = vec2(rnd(uint(px.x), uint(px.y), u.frame.x, stream), rnd(uint(px.x), uint(px.y), u.frame.x, stream + 0x8000u));
        for (uint j = 0u; j < n; ++j) {
            vec2 s = fract(vec2((float(j) + 0.5) / float(n), float(j) * 0.6180339887) + shift);
            float r = radius * sqrt(s.x), phi = 2.0 * PI * s.y;
            lit += sun_test(texel + r * vec2(cos(phi), sin(phi)), z, size);
        }
    }
    imageStore(o_signal, px, vec4(lit / float(n)));
}
