#version 450
// The raster pass's colour targets: the previous clip position (RGBA32F) and the signal (R32F).
layout(location = 0) in vec4 prev_clip;
layout(location = 1) flat in float signal;
layout(location = 0) out vec4 out_prev_clip;
layout(location = 1) out float out_signal;
void main() { out_prev_clip = prev_clip; out_signal = signal; }
