#version 450
// Signal 3, soft shadow of the area light: one shadow test per pixel against
// this frame's shadow map, rendered from one point of the light (Scherzer's
// iterative sampling; rrc's running mean averages the points over frames).
// Reference mode: called once per point of a grid on the light, adding
// visibility / count into the same image.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(local_size_x = 128, local_size_y = 1) in;

layout(set = 0, binding = 1) uniform sampler2D g_position;
layout(set = 0, binding = 2) uniform sampler2D g_normal_material;
layout(set = 0, binding = 3) uniform sampler2D point_map;
layout(set = 0, binding = 4, r32f) uniform image2D o_signal;
layout(push_constant) uniform Push {
    mat4 light_vp;  // the point's shadow-map view-projection
    uint pass;      // reference: 0..count-1
    uint count;     // 0: per-frame signal (store); > 0: reference accumulation
} pc;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= int(u.frame.z) || px.y >= int(u.frame.w)) return;
    vec4 nm = texelFetch(g_normal_material, px, 0);
    float vis = 1.0;
    if (material_of(nm) != MAT_BACKGROUND) {
        vec3 p = texelFetch(g_position, px, 0).xyz;
        // Normal offset of 1.5 texels at the receiver's distance.
        float size = u.lamp_point.w;
        float dist = dot(p - u.lamp_centre.xyz, u.lamp_facing.xyz);
        p += nm.xyz * (1.5 * 2.0 * dist * u.lamp_v.w / size);
        vec4 lc = pc.light_vp * vec4(p, 1.0);
        vec3 ndc = lc.xyz / lc.w;
        if (lc.w > 0.0 && all(lessThan(abs(ndc.xy), vec2(1.0)))) {
            ivec2 c = clamp(ivec2(floor((ndc.xy * 0.5 + 0.5) * size)), ivec2(0), ivec2(int(size) - 1));
            float blocker = lamp_linear_depth(texelFetch(point_map, c, 0).r);
            vis = lc.w <= blocker * (1.0 + u.lamp_facing.w) + 0.02 ? 1.0 : 0.0;
        }
    }
    if (pc.count == 0u) {
        imageStore(o_signal, px, vec4(vis));
    } else {
        float sum = pc.pass == 0u ? 0.0 : imageLoad(o_signal, px).r;
        imageStore(o_signal, px, vec4(sum + vis / float(pc.count)));
    }
}
