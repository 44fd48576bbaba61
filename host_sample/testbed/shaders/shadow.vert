#version 450
// Depth-only shadow-map pass: one light's view-projection (push constant).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec3 in_position;
layout(set = 0, binding = 1, std430) readonly buffer Objects { ObjectData objects[]; };
layout(push_constant) uniform Push {
    mat4 light_vp;
    uint object;
} pc;

void main() {
    gl_Position = pc.light_vp * (objects[pc.object].model * vec4(in_position, 1.0));
}
