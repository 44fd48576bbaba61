#version 450
// The paper's vertex shader (Figures 4-5): each vertex is transformed with
// this frame's model-view-projection and with the previous frame's, and the
// previous clip position is interpolated to every pixel.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(set = 0, binding = 1, std430) readonly buffer Objects { ObjectData objects[]; };
layout(push_constant) uniform Push { uint object; } pc;

layout(location = 0) out vec4 v_prev_clip;
layout(location = 1) out vec3 v_world;
layout(location = 2) out vec3 v_normal;
layout(location = 3) flat out uint v_material;
layout(location = 4) flat out uint v_object;

void main() {
    ObjectData o = objects[pc.object];
    vec4 world = o.model * vec4(in_position, 1.0);
    vec4 prev_world = o.prev_model * vec4(in_position, 1.0);
    gl_Position = u.view_proj * world;
    v_prev_clip = u.prev_view_proj * prev_world;
    v_world = world.xyz;
    v_normal = mat3(o.model) * in_normal;  // rigid motions and uniform scales only
    v_material = o.material.x;
    v_object = pc.object;
}
