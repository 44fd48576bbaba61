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
// `samples` taps of the pattern (pattern 1: samples/k stratified rotations);
// 3: the residual's base (below), into o_base only.
//
// The residual's base (README.md, "The pcf residual"): reference 3 writes only o_base,
// b = the mean of `samples` = M bilinear shadow compares (the test at the four texel centres
// around a point, weighted as a bilinear fetch: what a GPU's filtered depth-compare sampler
// returns in one fetch) at M points evenly spaced on the circle of radius
// rho = sqrt(R^2/2 - 1/3) around the receiver's map position, the first on the map's +x axis
// (rho matches the disk's variance per axis, R^2/4, with the bilinear tent's 1/6).  b is
// deterministic and continuous in the receiver's position, so rrc's history holds x - b,
// whose detail is b's error against the disk mean, not the shadow's edge.
//
// Confidence (README.md, "Finishing steps"; Scherzer et al. 2007): a tap at shadow-map position
// (x, y) texels tests the texel whose centre is (cx, cy) = floor(x, y) + 1/2;
// its confidence is c = 1 - 2 max(|x - cx|, |y - cy|) (1 at the centre, 0 on
// the texel's border, where the nearest-texel test is least sure).  With
// pc.confidence the k taps combine as s = sum(c_i t_i) / sum(c_i) (the plain
// mean if every c_i is 0) and w = mean(c_i), written to o_confidence; rrc's
// blend (lambda W H + (1 - lambda) w s) / W' then converges to E[w s] / E[w]
// = the confidence-weighted disk mean  int c t / int c  over the disk, not the
// disk mean.  The reference pass (reference 1) writes that weighted mean into
// o_confidence (a 16 x 16 midpoint rule per texel) beside the exact disk mean.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "disk_area.glsl"
#include "signal_modes.h"
layout(local_size_x = 128, local_size_y = 1) in;

layout(set = 0, binding = 1) uniform sampler2D g_position;
layout(set = 0, binding = 2) uniform sampler2D g_normal_material;
layout(set = 0, binding = 3) uniform sampler2D sun_map;
layout(set = 0, binding = 4, r32f) uniform writeonly image2D o_signal;
layout(set = 0, binding = 5, r32f) uniform writeonly image2D o_confidence;
layout(set = 0, binding = 6, r32f) uniform writeonly image2D o_base;
layout(push_constant) uniform Push {
    uint samples;     // brute force: taps
    uint reference;   // 0 per frame, 1 the exact target, 2 brute force, 3 the residual's base
    uint seed;        // the ensemble member: moves every random stream
    uint pattern;     // 0 uniform disk, 1 rotated Poisson
    uint confidence;  // non-zero: confidence-weighted taps (above); w in o_confidence
    uint env_base;    // signal_env.comp's (the push block is shared)
    uint base_taps;   // per frame: > 0 also writes the residual's base, that many compares, in this pass
} pc;

float sun_test(ivec2 c, float z, int size) {
    return z <= texelFetch(sun_map, clamp(c, ivec2(0), ivec2(size - 1)), 0).r ? 1.0 : 0.0;
}
float sun_test(vec2 texel, float z, int size) { return sun_test(ivec2(floor(texel)), z, size); }

// The bilinear shadow compare at q (texel i covers [i, i+1), its centre i + 1/2):
// the four texels i .. i + (1, 1) in one textureGather, centred on their shared
// corner i + 1 so that the gather's texel choice, floor(uv size - 1/2) = i, is
// exact; the sampler's CLAMP_TO_EDGE clamps them as sun_test does.  One gather
// is one sampled fetch where four texelFetch are four (on lavapipe each is a
// call of a generated function), and it reads the same texels, so the result is
// bit for bit the four fetches' (docs/guide/pcf-shadows.md, "When not to use it, and what it costs").
float bilinear_test(vec2 q, float z, int size) {
    vec2 p = q - 0.5, f = fract(p);
    ivec2 i = ivec2(floor(p));
    // Gather order: (i, i+1), (i+1, i+1), (i+1, i), (i, i).
    vec4 d = textureGather(sun_map, (vec2(i) + 1.0) / float(size), 0);
    vec4 t = vec4(lessThanEqual(vec4(z), d));
    return mix(mix(t.w, t.z, f.x), mix(t.x, t.y, f.x), f.y);
}

// The residual's base (above).
float base_estimate(vec2 texel, float radius, float z, int size, uint m) {
    float rho = sqrt(max(radius * radius * 0.5 - 1.0 / 3.0, 0.0)), sum = 0.0;
    for (uint j = 0u; j < m; ++j) {
        float phi = 2.0 * PI * float(j) / float(m);
        sum += bilinear_test(texel + rho * vec2(cos(phi), sin(phi)), z, size);
    }
    return sum / float(m);
}

// The tap's confidence: 1 - 2 max(|x - cx|, |y - cy|), (cx, cy) its texel's centre.
float tap_confidence(vec2 texel) {
    vec2 d = abs(texel - (floor(texel) + 0.5));
    return 1.0 - 2.0 * max(d.x, d.y);
}

// The confidence-weighted mean of the test over the disk, int c t / int c: a
// 16 x 16 midpoint rule in each texel of the disk's bounding box.
float weighted_disk_mean(vec2 centre, float radius, float z, int size) {
    ivec2 lo = ivec2(floor(centre - radius)), hi = ivec2(floor(centre + radius));
    float ct = 0.0, cs = 0.0;
    const int N = 16;
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
            float t = sun_test(ivec2(x, y), z, size), c_sum = 0.0;
            for (int j = 0; j < N; ++j)
                for (int i = 0; i < N; ++i) {
                    vec2 f = (vec2(i, j) + 0.5) / float(N);
                    if (length(vec2(x, y) + f - centre) > radius) continue;
                    c_sum += 1.0 - 2.0 * max(abs(f.x - 0.5), abs(f.y - 0.5));
                }
            ct += c_sum * t;
            cs += c_sum;
        }
    return cs > 0.0 ? ct / cs : 1.0;
}

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
        if (pc.reference == SAMPLE_PCF_BASE_PASS) {
            imageStore(o_base, px, vec4(1.0));
            return;
        }
        imageStore(o_signal, px, vec4(1.0));
        imageStore(o_confidence, px, vec4(1.0));
        if (pc.reference == 0u && pc.base_taps > 0u) imageStore(o_base, px, vec4(1.0));
        return;
    }
    vec3 p = texelFetch(g_position, px, 0).xyz + nm.xyz * u.sun_dir.w;  // normal offset
    vec4 lc = u.sun_vp * vec4(p, 1.0);
    int size = int(u.lamp_colour.w);
    vec2 texel = (lc.xy * 0.5 + 0.5) * float(size);
    float z = lc.z - u.ambient.w / 79.0;  // ortho depth spans 79 world units
    float radius = u.sun_colour.w;
    if (pc.reference == SAMPLE_PCF_BASE_PASS) {
        imageStore(o_base, px, vec4(base_estimate(texel, radius, z, size, pc.samples)));
        return;
    }
    if (pc.reference == 1u) {
        imageStore(o_signal, px, vec4(disk_mean(texel, radius, z, size)));
        imageStore(o_confidence, px, vec4(pc.confidence != 0u ? weighted_disk_mean(texel, radius, z, size) : 1.0));
        return;
    }
    uint k = u.frame.y;
    uint n = pc.reference != 0u ? pc.samples : k;
    // Random streams: 1 per-frame signal, 0x5eed + 2 brute force; the seed moves them all.
    uint stream = (pc.reference != 0u ? 0x5eedu + pc.reference : 1u) + 0x10000u * pc.seed;
    float lit = 0.0, c_lit = 0.0, c_sum = 0.0;  // plain sum; confidence-weighted sum and the weights
    if (pc.pattern == 1u) {
        uint rotations = max(n / k, 1u);
        float offset = rnd(uint(px.x), uint(px.y), u.frame.x, stream);
        for (uint r = 0u; r < rotations; ++r) {
            float a = 2.0 * PI * (float(r) + offset) / float(rotations);
            mat2 rot = mat2(cos(a), sin(a), -sin(a), cos(a));
            for (uint i = 0u; i < k; ++i) {
                vec2 q = texel + radius * (rot * u.poisson[i].xy);
                float t = sun_test(q, z, size), c = tap_confidence(q);
                lit += t;
                c_lit += c * t;
                c_sum += c;
            }
        }
        n = rotations * k;
    } else {
        vec2 shift = vec2(rnd(uint(px.x), uint(px.y), u.frame.x, stream), rnd(uint(px.x), uint(px.y), u.frame.x, stream + 0x8000u));
        for (uint j = 0u; j < n; ++j) {
            vec2 s = fract(vec2((float(j) + 0.5) / float(n), float(j) * 0.6180339887) + shift);
            float r = radius * sqrt(s.x), phi = 2.0 * PI * s.y;
            vec2 q = texel + r * vec2(cos(phi), sin(phi));
            float t = sun_test(q, z, size), c = tap_confidence(q);
            lit += t;
            c_lit += c * t;
            c_sum += c;
        }
    }
    bool weighted = pc.confidence != 0u && c_sum > 0.0;
    imageStore(o_signal, px, vec4(weighted ? c_lit / c_sum : lit / float(n)));
    imageStore(o_confidence, px, vec4(pc.confidence != 0u ? c_sum / float(n) : 1.0));
    // The residual's base in the per-frame pass itself: the pixel's G-buffer reads and its
    // transform to the light, most of a pass's cost, are paid once for both (the base pass,
    // reference 3, pays them again; docs/measurements/presets.md, "The pcf base's fetches").
    if (pc.reference == 0u && pc.base_taps > 0u) imageStore(o_base, px, vec4(base_estimate(texel, radius, z, size, pc.base_taps)));
}
