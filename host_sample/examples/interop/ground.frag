#version 450
// The raster pass's targets: depth (R32F, reversed by the projection), the previous clip position (RGBA32F), the signal (R32F).
layout(location = 0) in Ground { vec4 prev_clip; flat float signal; } ground;
layout(location = 0) out float out_depth;
layout(location = 1) out vec4 out_prev_clip;
layout(location = 2) out float out_signal;
void main() { out_depth = gl_FragCoord.z; out_prev_clip = ground.prev_clip; out_signal = ground.signal; }
