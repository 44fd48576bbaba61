// Shared by every shader of rrc-sample: the per-frame uniforms (frame_state.h
// mirrors them), the per-object data, material ids, hashing.
#ifndef RRC_SAMPLE_COMMON_GLSL
#define RRC_SAMPLE_COMMON_GLSL

#define MAT_BACKGROUND 0u
#define MAT_GROUND 1u
#define MAT_STONE 2u
#define MAT_SPHERE 3u
#define MAT_MOVER 4u

// rrc's mask bits, from the public list (include/rrc/rrc_values.h).
#include "rrc/rrc_values.h"
#define RRC_SAMPLE_UINT(name, value) const uint name = uint(value);
RRC_MASK_VALUES(RRC_SAMPLE_UINT)
#undef RRC_SAMPLE_UINT

#define MAX_TAPS 64

layout(set = 0, binding = 0, std140) uniform FrameUniforms {
    mat4 view_proj;
    mat4 prev_view_proj;
    mat4 inv_view_proj;
    mat4 sun_vp;
    mat4 lamp_point_vp;
    mat4 lamp_centre_vp;
    vec4 camera_pos;   // w: time
    vec4 sun_dir;      // w: normal offset
    vec4 sun_colour;   // w: PCF radius (texels)
    vec4 ambient;      // w: sun depth bias
    vec4 lamp_centre;  // w: near
    vec4 lamp_u;       // w: far
    vec4 lamp_v;       // w: tan(fov/2)
    vec4 lamp_point;   // w: lamp map size
    vec4 lamp_facing;  // w: relative bias
    vec4 lamp_colour;  // w: sun map size
    vec4 sphere;
    vec4 bump;
    vec4 mirror_eye;   // w 1: the eye the mirror reflects for (--frozen-mirror-view); w 0: the camera's
    uvec4 frame;       // index, taps, width, height
    vec4 poisson[MAX_TAPS];
} u;

struct ObjectData {
    mat4 model;
    mat4 prev_model;
    vec4 albedo;
    uvec4 material;
};

const float PI = 3.14159265358979;

// PCG hash (Jarzynski & Olano 2020).
uint pcg(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
// Uniform in [0, 1) from four integers (pixel x, y, frame, stream).
float rnd(uint a, uint b, uint c, uint d) {
    uint h = pcg(a ^ pcg(b ^ pcg(c ^ pcg(d))));
    return float(h >> 8) * (1.0 / 16777216.0);
}

uint material_of(vec4 normal_material) { return uint(normal_material.w + 0.5); }

// Lamp maps store standard perspective depth: back to the distance along the lamp's axis.
float lamp_linear_depth(float z) {
    float n = u.lamp_centre.w, f = u.lamp_u.w;
    return n * f / (f - z * (f - n));
}

#endif
