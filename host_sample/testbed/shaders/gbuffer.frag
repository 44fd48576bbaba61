#version 450
// G-buffer: previous clip position (rrc's PREV_CLIP input), motion vector
// and depth change (MOTION / MOTION_DEPTH), world normal + material, world
// position + object id, and the object id again as an integer for rrc.  Depth
// goes to the D32 reversed-z attachment.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec4 v_prev_clip;
layout(location = 1) in vec3 v_world;
layout(location = 2) in vec3 v_normal;
layout(location = 3) flat in uint v_material;
layout(location = 4) flat in uint v_object;

layout(location = 0) out vec4 o_prev_clip;
layout(location = 1) out vec4 o_motion;
layout(location = 2) out vec4 o_normal_material;
layout(location = 3) out vec4 o_position;
layout(location = 4) out uint o_object_id;

void main() {
    o_prev_clip = v_prev_clip;
    // Motion in uv units at the pixel centre: uv_prev - uv_cur, and the NDC
    // depth change (expected previous depth - current depth).
    vec2 size = vec2(u.frame.zw);
    vec2 uv_cur = gl_FragCoord.xy / size;
    vec2 uv_prev = (v_prev_clip.xy / v_prev_clip.w + 1.0) * 0.5;
    o_motion = vec4(uv_prev - uv_cur, v_prev_clip.z / v_prev_clip.w - gl_FragCoord.z, 0.0);
    o_normal_material = vec4(normalize(v_normal), float(v_material));
    // w: the object's index + 1 (the clear leaves 0 on the background), exact in
    // fp32; the host's visibility oracle reads which object a texel shows (oracle.h).
    o_position = vec4(v_world, float(v_object + 1u));
    // rrc's object id (rrc_vulkan_frame_desc.object_id): the same index + 1, 0 on the background.
    o_object_id = v_object + 1u;
}
