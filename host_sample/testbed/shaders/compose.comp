#version 450
// The displayed frame: the stone, ground and torus lit by the sun (times the
// PCF shadow signal) and by the area light (times the soft-shadow signal),
// the mirror sphere showing the env signal, the sky behind.  Tone mapped
// and written as 8-bit sRGB.  A disabled signal reads as 1 (unshadowed) or,
// for env, as one reflection of the smooth sphere at the pixel centre.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "env.glsl"
layout(local_size_x = 128, local_size_y = 1) in;

layout(set = 0, binding = 1) uniform sampler2D g_position;
layout(set = 0, binding = 2) uniform sampler2D g_normal_material;
layout(set = 0, binding = 3, r32f) uniform readonly image2D s_pcf;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D s_env;
layout(set = 0, binding = 5, r32f) uniform readonly image2D s_soft;
layout(set = 0, binding = 6, rgba8) uniform writeonly image2D o_colour;
layout(push_constant) uniform Push {
    uint signals;  // bit 0 pcf, 1 env, 2 soft
    // Display-only PCF remaps (README.md, "Finishing steps"; the chapter's Figure 9 e, f), applied to what is
    // shown, never to rrc's history: bit 0 smoothstep(e0, e1, pcf), bit 1 the threshold
    // pcf >= x (after the smoothstep when both are on).  Only the accumulated frame (set 0).
    uint pcf_remap;
    float e0, e1, x;
} pc;

vec3 albedo(uint m, vec3 p) {
    if (m == MAT_GROUND) {
        float c = mod(floor(p.x * 0.5) + floor(p.z * 0.5), 2.0);
        return mix(vec3(0.42, 0.4, 0.34), vec3(0.6, 0.57, 0.5), c);
    }
    if (m == MAT_STONE) return vec3(0.8, 0.76, 0.68);
    if (m == MAT_MOVER) return vec3(0.78, 0.2, 0.1);
    return vec3(0.85);
}

vec3 srgb(vec3 c) {
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    vec2 size = vec2(u.frame.zw);
    if (px.x >= int(size.x) || px.y >= int(size.y)) return;
    vec4 nm = texelFetch(g_normal_material, px, 0);
    uint m = material_of(nm);
    vec3 colour;
    vec2 ndc = (vec2(px) + 0.5) / size * 2.0 - 1.0;
    if (m == MAT_BACKGROUND) {
        vec4 fp = u.inv_view_proj * vec4(ndc, 0.5, 1.0);
        colour = env_radiance(fp.xyz / fp.w - u.camera_pos.xyz);
    } else {
        vec3 p = texelFetch(g_position, px, 0).xyz, n = normalize(nm.xyz);
        float pcf = (pc.signals & 1u) != 0u ? imageLoad(s_pcf, px).r : 1.0;
        if ((pc.pcf_remap & 1u) != 0u) pcf = smoothstep(pc.e0, pc.e1, pcf);
        if ((pc.pcf_remap & 2u) != 0u) pcf = pcf >= pc.x ? 1.0 : 0.0;
        float soft = (pc.signals & 4u) != 0u ? imageLoad(s_soft, px).r : 1.0;
        vec3 to_lamp = u.lamp_centre.xyz - p;
        float d2 = dot(to_lamp, to_lamp);
        vec3 l = to_lamp * inversesqrt(d2);
        float lamp_cos = max(dot(n, l), 0.0) * max(dot(-l, u.lamp_facing.xyz), 0.0);
        vec3 light = u.ambient.rgb + u.sun_colour.rgb * max(dot(n, u.sun_dir.xyz), 0.0) * pcf +
                     u.lamp_colour.rgb * lamp_cos / d2 * soft;
        colour = albedo(m, p) * light;
        if (m == MAT_SPHERE) {
            vec3 env = (pc.signals & 2u) != 0u ? imageLoad(s_env, px).rgb : sphere_sample(ndc);
            colour = 0.15 * colour + 0.85 * env;
        }
    }
    colour *= 1.1;
    colour = colour / (1.0 + colour);  // Reinhard
    imageStore(o_colour, px, vec4(srgb(colour), 1.0));
}
