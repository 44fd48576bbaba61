// Independent double-precision CPU reference of docs/CONVENTIONS.md.
//
// It validates the GLSL kernel, so it shares no code with compute/ or plugin/:
// the math is re-derived from the conventions, in double, with GLM for the
// CAMERA matrices.  One call computes one frame from the previous frame's
// stored state; tests feed it the KERNEL's previous outputs so that a one-frame
// comparison cannot drift.
//
// Exactness vs. the fp32 kernel: every comparison the conventions make (hit
// test, border test, w > 0, background taps, nearest texel) is decided here
// in exact-ish double math.  Alongside, the reference carries a first-order
// bound on how far the kernel's fp32 value of each intermediate can be from
// the exact one (see error_bound.h) and flags pixels whose decision that
// error could flip:
//   near_threshold     the hit/miss decision itself may differ;
//   near_nearest_edge  the nearest texel (age, NEAREST history) may differ.
// Tests skip the mask comparison on near_threshold pixels and the age /
// nearest-history comparison on near_nearest_edge pixels.
//
// Choices made here where docs/CONVENTIONS.md is silent (keep the kernel in step):
//  * Precedence for the current pixel: invalid depth -> INVALID_GEOMETRY; else
//    background -> BACKGROUND (reprojection data is not looked at); else
//    non-finite reprojection data -> INVALID_GEOMETRY.
//  * INVALID_SAMPLE is set whenever some channel's sample is invalid, on any
//    pixel (background and invalid-geometry pixels included).
//  * A "do not cache" pixel is a plain miss: no mask bit.
//  * The shading cache (reference/cache.h): REFRESHED replaces HIT where a
//    REUSE channel refreshes; accumulating channels still take the pixel as a
//    hit.  The ages the refresh reads are the nearest texel's (flagged by
//    near_nearest_edge where that texel may differ).
//  * Plain MOTION with STANDARD depth and far = +inf linearises as n/(1 - z).
//
// The deviation gate (reference/gate.h, docs/CONVENTIONS.md "The deviation
// gate") keeps a per-pixel state (beta, varsigma) that the kernel never reads
// back.  A test therefore takes history, age and weight from the kernel's
// outputs as above, but the gate's state from the reference's OWN previous
// FrameResult (carry_gate_state).  The two states then differ by the kernel's
// fp32 roundings over the frames the state remembers, and by whatever the
// kernel did differently on a pixel the reference flagged: each state value
// carries a bound on that difference (infinite on near_threshold and
// near_nearest_edge pixels, where the kernel may have taken another case of
// the table or another n_prev), and ChannelResult::gate_uncertain flags the
// pixels whose stored age that bound leaves open.
#ifndef RRC_REFERENCE_H
#define RRC_REFERENCE_H

#include <rrc/rrc.h>

#include <cstdint>
#include <vector>

namespace rrc_ref {

// The previous frame's stored state of one channel (the kernel's output).
struct ChannelHistory {
    std::vector<float> history;  // W*H*components, as stored (fp16 values for fp16 channels)
    std::vector<uint16_t> age;   // W*H
    std::vector<float> weight;   // W*H for confidence channels; empty otherwise
    // The deviation gate's state (gate channels): beta and varsigma (the
    // running mean and mean square of the deviation) and the bounds on how far
    // the kernel's can be from them; W*H each, or empty = all zero.  Never the
    // kernel's (it is not read back): the reference's own, carry_gate_state.
    std::vector<double> gate_beta, gate_sq, gate_beta_err, gate_sq_err;
};

struct PreviousFrame {
    bool valid = false;                    // false: first frame / after reset or resize -> all misses
    std::vector<float> depth;              // previous frame's depth exactly as the host passed it (W*H)
    std::vector<uint32_t> object_id;       // previous frame's object ids (object-id contexts), W*H
    std::vector<ChannelHistory> channels;  // in the context's channel order
};

struct ChannelResult {
    std::vector<double> out;     // the stored history: fp16 channels: fp16_round(exact); fp32: exact
    std::vector<double> exact;   // the value before the fp16 rounding (== out for fp32 channels)
    std::vector<uint16_t> age;   // W*H
    std::vector<double> weight;  // W*H for confidence channels; empty otherwise
    // Rectification (reference/finish.h): where it applied, the bound on the
    // kernel's error that the fp32 box (mu +- gamma sigma) adds to `exact`,
    // per component, 0 elsewhere; and the pixels whose H the clamp moved.
    std::vector<double> rectify_err;  // W*H*components
    std::vector<uint8_t> rectified;   // W*H
    // The lag detector (reference/finish.h): where it applied, n_a (else the
    // previous age), whether an fp32 evaluation could give another n_a
    // (compare such a pixel's age and value loosely), and its confidence c
    // (1 where it did not apply).
    std::vector<uint16_t> antilag_age;      // W*H
    std::vector<uint8_t> antilag_uncertain;  // W*H
    std::vector<double> antilag_c;          // W*H
    // The blur bound (reference/finish.h): where it applied, the cap N (else
    // 65535), whether it capped the age (N < n_prev), whether an fp32
    // evaluation could give another age (the smaller of N and the lag
    // detector's n_a, against n_prev), and b.
    std::vector<uint16_t> blur_age;      // W*H
    std::vector<uint8_t> blur_capped;     // W*H
    std::vector<uint8_t> blur_uncertain;  // W*H
    std::vector<double> blur_b;           // W*H
    // The view lobe (reference/view_lobe.h): where it applied, the cap n_v
    // (else 65535), whether it capped the age (n_v < n_prev), whether an fp32
    // evaluation could give another stored age, and theta (radians).
    std::vector<uint16_t> view_age;      // W*H
    std::vector<uint8_t> view_capped;     // W*H
    std::vector<uint8_t> view_uncertain;  // W*H
    std::vector<double> view_theta;       // W*H
    // The deviation gate (reference/gate.h): the stored state (beta, varsigma)
    // and its bounds (as ChannelHistory: the next frame's gate state); where
    // the gate applied, the cap N_g (else 65535), whether it capped the age
    // (N_g < n_prev), whether the kernel's fp32 state and arithmetic could give
    // another stored age (the smallest of the caps against n_prev, as
    // blur_uncertain), and the deviation d (0 elsewhere).
    std::vector<double> gate_beta, gate_sq, gate_beta_err, gate_sq_err;  // W*H
    std::vector<uint16_t> gate_age;                                      // W*H
    std::vector<uint8_t> gate_capped;                                    // W*H
    std::vector<uint8_t> gate_uncertain;                                 // W*H
    // The stored ages the kernel may take there (== age where certain): the
    // range N_g's fp32 bound allows, composed with the other caps.
    std::vector<uint16_t> gate_age_lo, gate_age_hi;  // W*H
    std::vector<double> gate_d;                                          // W*H
    // Channels with a fill (fill_age > 0): the displayed value, spatial_fill
    // of `out` with this frame's depth and fallback (as read back standalone:
    // not rounded to fp16), a gated channel's neighbours weighed by the gate
    // state this frame stored (gate_beta, gate_sq); with a residual (docs/CONVENTIONS.md, "The
    // residual"), that value (or `out`) plus this frame's base b, a b that is
    // not finite counting as 0; empty otherwise.
    std::vector<double> shown;  // W*H*components
};

struct FrameResult {
    std::vector<uint8_t> mask;  // RRC_MASK_* bits
    std::vector<ChannelResult> channels;
    rrc_frame_stats stats{};  // counted from mask as the library counts them (misses exclude refreshed)
    uint64_t refreshed = 0;   // pixels with RRC_MASK_REFRESHED

    // Per-pixel diagnostics (see the header comment).
    std::vector<uint8_t> near_threshold;
    std::vector<uint8_t> near_nearest_edge;
    // NaN where the pixel never reached the epsilon test (no valid previous
    // frame, background, invalid geometry, do-not-cache, non-finite values).
    std::vector<double> diff, eps;  // diff = fetched - expected (linear depths for plain MOTION)
    std::vector<double> diff_err;   // error bound of the kernel's diff (times Options::error_scale)
    std::vector<double> expected, fetched;
    // NaN for background and invalid-geometry pixels.
    std::vector<double> uv_prev_x, uv_prev_y;
};

struct Options {
    // Multiplies every fp32 error bound.  1 = the first-order worst case of a
    // straightforward fp32 evaluation of the conventions' formulas.  0 turns
    // the near_* flags into "exactly on a threshold" only.  Measured against
    // the lavapipe kernel (tests/kernels/kernel_reference_test.cpp, 15 cases): no mask
    // flip outside the margin at 1 or 0.5, 3 at 0.25 (camera_standard), so the
    // worst case is not loose by much.  FLOAT32's default 4-ulp epsilon lies
    // inside that error for most hits: expect them all flagged (and a few real
    // flips), i.e. the hit decision there is within fp32 noise.
    double error_scale = 1.0;
};

// Computes one frame.  Arrays in `frame` are read as the C API documents them;
// throws std::invalid_argument on NULL required arrays or on a valid `prev`
// whose arrays do not match the context's size and channels.
FrameResult run_frame(const rrc_context_desc& ctx, const PreviousFrame& prev, const rrc_frame_desc& frame, const Options& options = {});

// The stored state run_frame's result leaves for the next frame (values as the
// kernel would store them: fp32 channels rounded to float), for multi-frame
// runs of the reference on its own.
PreviousFrame as_previous(const rrc_context_desc& ctx, const rrc_frame_desc& frame, const FrameResult& result);

// Replaces prev's gate state (every channel's) with the one `own` stored: for
// a `prev` built from the kernel's outputs (tests/support/kernel_state.h),
// which cannot hold the kernel's gate state.  `own` must be the reference's
// result of the frame prev describes.
void carry_gate_state(PreviousFrame& prev, const FrameResult& own);

// Clamp to +-65504, then round to the nearest fp16 value, ties to even.
// The result is exactly representable in fp16.  NaN stays NaN.
double fp16_round(double v);

// The ulp of v as an fp32 value: 2^(floor(log2|f|) - 23) with f = float(v);
// 2^-149 for f = 0 and for fp32-denormal f.
double ulp_fp32(double v);

// The hit-test tolerance for this context's test at expected depth e (a
// linear depth for LINEAR contexts and plain MOTION; NDC z otherwise):
// relative tests: tau * e; NDC tests: the absolute epsilon if given, else
// scale * increment of the depth format (FLOAT32: scale * ulp_fp32(e)).
double epsilon_for(const rrc_context_desc& ctx, double expected_depth);

}  // namespace rrc_ref

#endif
