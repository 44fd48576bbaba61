#version 450
// The raster pass: a 6 x 6 ground quad at y = 0; its clip position now and in the previous frame (PREV_CLIP, "Inputs"), the signal.
layout(push_constant) uniform Camera { mat4 view_proj, prev_view_proj; } camera;
layout(location = 0) out Ground { vec4 prev_clip; flat float signal; } ground;
void main() {
    const vec4 world = vec4(6.0 * vec2(gl_VertexIndex & 1, gl_VertexIndex >> 1) - 3.0, 0.0, 1.0).xzyw;
    gl_Position = camera.view_proj * world;
    ground.prev_clip = camera.prev_view_proj * world;  // linear in the surface point: interpolates exactly
    ground.signal = float(1 + 2 * gl_InstanceIndex);  // firstInstance is the frame: 1, then 3
}
