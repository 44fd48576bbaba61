#version 450
// Signal 2, env-mapped bump mapping: k sub-pixel samples of the mirror
// sphere per pixel.  The samples are a stratified k-point set (x stratified,
// y by the golden ratio) shifted by a random toroidal offset per pixel and
// frame (Cranley-Patterson), so each frame is an unbiased estimate of the
// pixel integral.  Reference mode: `samples` points of the same kind.
// Pixels that do not show the sphere get 0 (alpha 0 marks them).
// The per-frame signal (set 0) with `base` non-zero also writes o_base, a
// deterministic estimate the env channel's residual subtracts (README.md,
// "The env residual"), one of SAMPLE_ENV_BASE_* (signal_modes.h says which is
// which; the filtered one is env.glsl's sphere_filtered).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "env.glsl"
#include "signal_modes.h"
layout(local_size_x = 128, local_size_y = 1) in;

layout(set = 0, binding = 1) uniform sampler2D g_normal_material;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D o_signal;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D o_base;
// pattern and confidence: signal_pcf.comp's
layout(push_constant) uniform Push { uint samples; uint reference; uint seed; uint pattern; uint confidence; uint base; } pc;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= int(u.frame.z) || px.y >= int(u.frame.w)) return;
    bool base = pc.reference == 0u && pc.base != 0u;
    if (material_of(texelFetch(g_normal_material, px, 0)) != MAT_SPHERE) {
        imageStore(o_signal, px, vec4(0.0));
        if (base) imageStore(o_base, px, vec4(0.0));
        return;
    }
    uint n = pc.reference != 0u ? pc.samples : u.frame.y;
    // Streams: 2 per frame, 0x5eed + 2 reference, 0x5eed + 4 brute force; the seed moves them all.
    uint stream = (pc.reference != 0u ? 0x5eedu + 2u * pc.reference : 2u) + 0x10000u * pc.seed;
    vec2 shift = vec2(rnd(uint(px.x), uint(px.y), u.frame.x, stream), rnd(uint(px.x), uint(px.y), u.frame.x, stream + 1u));
    vec2 size = vec2(u.frame.zw);
    vec2 centre = (vec2(px) + 0.5) / size * 2.0 - 1.0;
    if (base)
        imageStore(o_base, px, vec4(pc.base == SAMPLE_ENV_BASE_FILTERED ? sphere_filtered(centre, 2.0 / size)
                                                                   : sphere_sample(centre, pc.base == SAMPLE_ENV_BASE_CENTRE, pc.base == SAMPLE_ENV_BASE_SMOOTH),
                                  1.0));
    vec3 sum = vec3(0.0);
    for (uint j = 0u; j < n; ++j) {
        vec2 o = fract(vec2((float(j) + 0.5) / float(n), float(j) * 0.6180339887) + shift);
        sum += sphere_sample((vec2(px) + o) / size * 2.0 - 1.0);
    }
    imageStore(o_signal, px, vec4(sum / float(n), 1.0));
}
