// The frame's depth conventions, shared by every pass that reads depth
// (compute/rrc_module_*.comp): the depth mode, the frame's push constants, the
// previous depth (the fill and copy-out passes, bound as the next frame, find
// this frame's depth there) and what background and invalid depth are
// (docs/CONVENTIONS.md).  The hit test itself is rrc_reproject.glsl.
#ifndef RRC_DEPTH_GLSL
#define RRC_DEPTH_GLSL

#include "rrc_values.glsl"  // rrc_depth_mode, RRC_PC_OFFSET_*, ids

layout(constant_id = RRC_SPEC_DEPTH_MODE) const uint DEPTH_MODE = RRC_DEPTH_MODE_STANDARD;

// ---- Per-frame parameters (RRC_PC_SIZE = 128 bytes: the guaranteed minimum)
// Each member at its RRC_PC_OFFSET_* (rrc_kernel_interface.h): the std430
// offsets, asserted against plugin/accumulate_pipeline.h's FramePushConstants.
layout(push_constant) uniform Frame {
    layout(offset = RRC_PC_OFFSET_M) mat4 M;                    // CAMERA: VP_prev * inverse(VP_cur), formed in double on the CPU
    layout(offset = RRC_PC_OFFSET_INV_ROW3) vec4 inv_row3;      // CAMERA + LINEAR: row 3 of inverse(VP_cur)
    layout(offset = RRC_PC_OFFSET_JITTER) vec4 jitter;          // xy: this frame's sample offset (pixels), zw: the previous frame's
    layout(offset = RRC_PC_OFFSET_MOTION_SCALE) vec2 motion_scale;  // multiplies motion vectors into uv units
    layout(offset = RRC_PC_OFFSET_EPS) float eps;               // see EPS_KIND
    layout(offset = RRC_PC_OFFSET_NEAR_PLANE) float near_plane; // plain MOTION on NDC depth: linearisation
    layout(offset = RRC_PC_OFFSET_FAR_PLANE) float far_plane;   //   (may be +inf for REVERSED)
    layout(offset = RRC_PC_OFFSET_BG_THRESHOLD) float bg_threshold;  // LINEAR: d >= this is background
    layout(offset = RRC_PC_OFFSET_PREV_VALID) uint prev_valid;  // 0 on the first frame, after reset or resize
    layout(offset = RRC_PC_OFFSET_REFRESH_PHASE) uint refresh_phase;  // frame_index mod refresh_period (rrc_cache.glsl)
} pc;

// False for the invocations beyond the image (the dispatch rounds up): they
// run on a clamped pixel and store nothing.  A kernel guards its stores with
// it instead of returning early, because lavapipe runs everything after a
// divergent return lane by lane, push-constant loads included (CAMERA's
// matrix: docs/design/inside-the-kernel.md).
bool rrc_store = true;

bool rrc_finite(float x) { return !isnan(x) && !isinf(x); }
bool rrc_finite4(vec4 v) { return !any(isnan(v)) && !any(isinf(v)); }

bool rrc_is_background(float d) {
    if (DEPTH_MODE == RRC_DEPTH_MODE_STANDARD) return d >= 1.0;
    if (DEPTH_MODE == RRC_DEPTH_MODE_REVERSED) return d <= 0.0;
    return d >= pc.bg_threshold;  // +inf included
}

// Non-finite depth, or depth outside its mode's range (NaN compares false).
bool rrc_is_invalid_depth(float d) {
    if (isnan(d)) return true;
    if (DEPTH_MODE == RRC_DEPTH_MODE_STANDARD) return !(d >= 0.0) || isinf(d);
    if (DEPTH_MODE == RRC_DEPTH_MODE_REVERSED) return !(d <= 1.0) || isinf(d);
    return !(d > 0.0);  // LINEAR: +inf is background, not invalid
}

float rrc_linearize(float z) {
    float n = pc.near_plane, f = pc.far_plane;
    if (DEPTH_MODE == RRC_DEPTH_MODE_STANDARD) return n * f / (f - z * (f - n));
    if (DEPTH_MODE == RRC_DEPTH_MODE_REVERSED) return isinf(f) ? n / z : n * f / (n + z * (f - n));
    return z;
}

#endif
