#version 450
// The displayed soft shadow.  rrc's running mean is exact only once a pixel
// has accumulated many light points; a pixel the cache missed has one binary
// sample.  Where rrc's mask says miss, this shows a PCSS estimate from the
// shadow map of the light's centre instead; on hits it blends the PCSS
// estimate in as a prior worth `prior` samples:
//     shown = (n * accumulated + prior * pcss) / (n + prior),  n = cache age.
// The history rrc keeps is never touched: the fallback only affects display.
//
// PCSS (Fernando 2005) with the light's real size: a blocker search over the
// region of the centre map that can hold occluders of the light seen from the
// receiver, the mean blocker depth d_b, then PCF over the penumbra width
// a (d_r - d_b) / d_b (light half size a, receiver depth d_r).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(local_size_x = 128, local_size_y = 1) in;

layout(set = 0, binding = 1) uniform sampler2D g_position;
layout(set = 0, binding = 2) uniform sampler2D g_normal_material;
layout(set = 0, binding = 3) uniform sampler2D centre_map;
layout(set = 0, binding = 4, r32f) uniform readonly image2D accumulated;
layout(set = 0, binding = 5, r8ui) uniform readonly uimage2D rrc_mask;
layout(set = 0, binding = 6, r16ui) uniform readonly uimage2D age;
layout(set = 0, binding = 7, r32f) uniform writeonly image2D o_shown;
layout(set = 0, binding = 8, r32f) uniform writeonly image2D o_pcss;
// mode 0: PCSS and the displayed blend (after rrc); mode 1: the PCSS estimate only,
// before rrc, which takes it as the soft channel's fill fallback (--soft-fill).
// Both modes compute the same estimate (the same per-frame random angle).
// mode 2: the stable estimate only, the base of the soft residual (rrc's
// rrc_channel_desc.residual; README.md, "The soft residual"): every pixel and frame
// the same taps (angle 0), each tap bilinear, so it carries no noise that
// changes from frame to frame and moves continuously with the surface point;
// 48 search and 64 filter taps, because what b varies by where the shadow does
// not reaches the output as flicker under a moving camera (docs/measurements/PERFORMANCE.md,
// "The soft residual: what it buys, measured").
layout(push_constant) uniform Push { float prior; uint mode; } pc;

const uint SEARCH0 = 16u, FILTER0 = 24u;  // modes 0 and 1
const uint SEARCH2 = 48u, FILTER2 = 64u;  // mode 2

float blocker_depth(ivec2 c, int size) {
    return lamp_linear_depth(texelFetch(centre_map, clamp(c, ivec2(0), ivec2(size - 1)), 0).r);
}

// The stable estimate's taps (mode 2) are bilinear: each reads the four texels
// about q with their bilinear weights, so that the estimate moves continuously
// with the surface point instead of in texel steps.
void bilinear_taps(vec2 q, int size, out ivec2 t00, out vec4 w) {
    vec2 x = q * float(size) - 0.5, f = fract(x);
    t00 = ivec2(floor(x));
    w = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= int(u.frame.z) || px.y >= int(u.frame.w)) return;
    vec4 nm = texelFetch(g_normal_material, px, 0);
    float pcss = 1.0;
    if (material_of(nm) != MAT_BACKGROUND) {
        int size = int(u.lamp_point.w);
        float tan_half = u.lamp_v.w;
        vec3 p = texelFetch(g_position, px, 0).xyz;
        float dist = dot(p - u.lamp_centre.xyz, u.lamp_facing.xyz);
        p += nm.xyz * (1.5 * 2.0 * dist * tan_half / float(size));
        vec4 lc = u.lamp_centre_vp * vec4(p, 1.0);
        float d_r = lc.w;
        vec2 uv = (lc.xy / lc.w) * 0.5 + 0.5;
        float a = length(u.lamp_u.xyz);  // half size of the (square) light
        float bias = d_r * u.lamp_facing.w + 0.02;
        float angle = pc.mode == 2u ? 0.0 : 2.0 * PI * rnd(uint(px.x), uint(px.y), u.frame.x, 3u);
        // Occluders lie at least 1/4 of the way from the light; the cone of
        // the light seen from the receiver has half-width a (d_r - z) / d_r at depth z.
        float z_min = max(0.25 * d_r, u.lamp_centre.w);
        float search_uv = a * (d_r - z_min) / (d_r * z_min * 2.0 * tan_half);
        const bool SMOOTH = pc.mode == 2u;
        const uint SEARCH = SMOOTH ? SEARCH2 : SEARCH0, FILTER = SMOOTH ? FILTER2 : FILTER0;
        const ivec2 O[4] = ivec2[4](ivec2(0, 0), ivec2(1, 0), ivec2(0, 1), ivec2(1, 1));
        float sum = 0.0, found = 0.0;
        for (uint i = 0u; i < SEARCH; ++i) {
            float r = sqrt((float(i) + 0.5) / float(SEARCH)), t = float(i) * 2.39996323 + angle;
            vec2 q = uv + search_uv * r * vec2(cos(t), sin(t));
            if (SMOOTH) {
                ivec2 t00;
                vec4 w;
                bilinear_taps(q, size, t00, w);
                for (int j = 0; j < 4; ++j) {
                    float z = blocker_depth(t00 + O[j], size);
                    if (z + bias < d_r) { sum += w[j] * z; found += w[j]; }
                }
            } else {
                float z = blocker_depth(ivec2(floor(q * float(size))), size);
                if (z + bias < d_r) { sum += z; found += 1.0; }
            }
        }
        if (found > 0.0 && lc.w > 0.0) {
            float d_b = sum / found;
            float filter_uv = a * (d_r - d_b) / (d_r * d_b * 2.0 * tan_half) + 0.5 / float(size);
            float lit = 0.0;
            for (uint i = 0u; i < FILTER; ++i) {
                float r = sqrt((float(i) + 0.5) / float(FILTER)), t = float(i) * 2.39996323 + angle;
                vec2 q = uv + filter_uv * r * vec2(cos(t), sin(t));
                if (SMOOTH) {
                    ivec2 t00;
                    vec4 w;
                    bilinear_taps(q, size, t00, w);
                    for (int j = 0; j < 4; ++j) lit += d_r <= blocker_depth(t00 + O[j], size) + bias ? w[j] : 0.0;
                } else {
                    lit += d_r <= blocker_depth(ivec2(floor(q * float(size))), size) + bias ? 1.0 : 0.0;
                }
            }
            pcss = lit / float(FILTER);
            // A blocker that enters the search region enters by its bilinear weight, not at once.
            if (SMOOTH) pcss = mix(1.0, pcss, min(found, 1.0));
        }
    }
    if (pc.mode >= 1u) {
        imageStore(o_pcss, px, vec4(pcss));
        return;
    }
    uint mask = imageLoad(rrc_mask, px).r;
    float n = float(imageLoad(age, px).r);
    float acc = imageLoad(accumulated, px).r;
    float shown = (mask & RRC_MASK_HIT) != 0u ? (n * acc + pc.prior * pcss) / max(n + pc.prior, 1e-6) : pcss;
    if ((mask & RRC_MASK_BACKGROUND) != 0u) shown = 1.0;
    imageStore(o_shown, px, vec4(shown));
    imageStore(o_pcss, px, vec4(pcss));
}
