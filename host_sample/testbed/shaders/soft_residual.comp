#version 450
// The soft shadow accumulated as a residual (README.md, "The soft residual"):
// rrc accumulates s - b, where b is the stable PCSS estimate (soft_fallback.comp
// mode 2: the same taps at every pixel and frame, so b changes only where the
// scene or the light does), and the host adds this frame's b back to rrc's
// output.  b is deterministic, so the residual's noise is the sample's own,
// and where the shadow moves the history lags behind s - b, not behind s:
// the lag is the part of the shadow's change that b did not follow.
//   mode 0, before rrc: residual = s - b; zero = 0 (the fill's fallback for
//                       the residual: its prior is b itself)
//   mode 1, after rrc:  shown = rrc's output + b (in place)
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(local_size_x = 128, local_size_y = 1) in;

layout(set = 0, binding = 1, r32f) uniform readonly image2D raw;       // s: this frame's one-light-point sample
layout(set = 0, binding = 2, r32f) uniform readonly image2D base;      // b: the stable PCSS estimate
layout(set = 0, binding = 3, r32f) uniform writeonly image2D residual; // rrc's soft samples
layout(set = 0, binding = 4, r32f) uniform image2D shown;              // rrc's soft output, then the displayed shadow
layout(set = 0, binding = 5, r32f) uniform writeonly image2D zero;     // rrc's soft fallback
layout(push_constant) uniform Push { uint mode; } pc;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= int(u.frame.z) || px.y >= int(u.frame.w)) return;
    float b = imageLoad(base, px).r;
    if (pc.mode == 0u) {
        imageStore(residual, px, vec4(imageLoad(raw, px).r - b));
        imageStore(zero, px, vec4(0.0));
    } else {
        imageStore(shown, px, vec4(imageLoad(shown, px).r + b));
    }
}
