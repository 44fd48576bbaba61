// The 0.4 finishing steps of docs/CONVENTIONS.md ("Finishing steps (0.4)"):
// rectification of the resampled history, the Gaussian history filter's
// weights, and the spatial fill of young pixels.  Re-derived from the
// conventions in double; nothing here is shared with compute/ or plugin/.
#ifndef RRC_REFERENCE_FINISH_H
#define RRC_REFERENCE_FINISH_H

#include <rrc/rrc.h>

#include <cstdint>
#include <vector>

#include "params.h"

namespace rrc_ref {

// ---- Rectification -------------------------------------------------------

// The clamp box of pixel (i, j): per component mu +- gamma sigma over the
// valid samples of the clamped 3x3 neighbourhood of this frame's input.
struct RectifyBox {
    unsigned taps = 0;  // m, the valid taps (clamped repeats count)
    double mu[4] = {0, 0, 0, 0}, sigma[4] = {0, 0, 0, 0};
    double lo[4] = {0, 0, 0, 0}, hi[4] = {0, 0, 0, 0};
    // First-order bound on how far an fp32 evaluation of lo / hi (the one-pass
    // sums of s and s^2, sqrt(max(E[s^2] - mu^2, 0))) can be from the exact
    // ones: sigma's cancellation makes this sqrt(u) * |s| large where the 9
    // samples (nearly) agree.
    double err[4] = {0, 0, 0, 0};
    // The parts of err: mu's and sigma's own bounds (the lag detector uses
    // sigma with its own gamma).
    double mu_err[4] = {0, 0, 0, 0}, sigma_err[4] = {0, 0, 0, 0};
};

// A sample of the channel's input counts when every component (and, with
// confidence, the confidence) is finite.
bool sample_valid(const ChannelParams& ch, const rrc_channel_input& in, size_t pixel);

RectifyBox rectify_box(const ChannelParams& ch, const rrc_channel_input& in, int width, int height, int i, int j);

// H_k <- min(max(H_k, lo_k), hi_k) for k < components.  Returns, per
// component, the bound on the kernel's clamped value's error from the box's
// error (0 where H lies inside the box by more than that error).
void rectify_history(const RectifyBox& box, unsigned components, double* h, double* err);

// ---- The lag detector -------------------------------------------------------

struct Antilag {
    double d = 0.0;  // the relative gap, max over components
    double c = 1.0;  // the history's confidence
    unsigned age = 0;  // n_a = floor(c * n_prev)
    // The ages an fp32 evaluation can give: the range of n_a over d within the
    // bound of the fp32 box and of the resampled H (a relative 1e-4 of the
    // values: the sample position's share, tests/support/tolerance.h, is
    // below it), and c within 4 ulp.  age_lo == age_hi where n_a is certain.
    unsigned age_lo = 0, age_hi = 0;
};

// n_a for the resampled (unclamped) history h with age n_prev >= 1, from the
// box's mu and sigma (rectify_box; its gamma is not used).
Antilag antilag_age(const ChannelParams& ch, const RectifyBox& box, const double* h, unsigned n_prev);

// ---- The blur bound -----------------------------------------------------------

struct BlurBound {
    double b = 0.0;          // the fetch's blur: max over axes of its weights' second moment, px^2
    unsigned age = 65535;    // N = floor(B / b), at most RRC_MAX_AGE_CAP (b = 0: no cap)
    // The caps an fp32 evaluation can give: N over the fraction within the
    // sample position's bound (q_err on each axis; a fraction whose floor may
    // differ takes both sides) and b, B / b within 4 ulp.  age_lo <= age <= age_hi.
    unsigned age_lo = 65535, age_hi = 65535;
};

// The second moment about the fetch point of one axis's resampling weights at
// fraction f (taps at -1, 0, 1, 2 relative to floor(q - 0.5)): BILINEAR
// f(1 - f), GAUSSIAN f(1 - f) + 2g (the moment summed over gaussian_weights),
// NEAREST and CATMULL_ROM 0 (docs/CONVENTIONS.md, "The blur bound").
double resampling_blur(const ChannelParams& ch, double f);

// The age cap of a blend whose history is fetched at q = (qx, qy) (the
// previous frame's sample coordinate), each known within q_err.
BlurBound blur_bound_age(const ChannelParams& ch, double qx, double qy, double q_err);

// ---- The Gaussian history filter -------------------------------------------

// Per-axis weights of taps i0 - 1 .. i0 + 2 for fraction t: the 3-tap blur
// [g, 1 - 2g, g] convolved with the bilinear [1 - t, t].
void gaussian_weights(double t, double g, double w[4]);

// ---- The spatial fill ------------------------------------------------------

// The depth proxy delta of the fill from this frame's depth (LINEAR d,
// STANDARD 1/(1 - z), REVERSED 1/z).
double fill_depth_proxy(rrc_depth_mode mode, double depth);

// One channel's outputs after the frame, as the fill reads them.
struct FillInputs {
    const float* values;    // W*H*components: the channel's history as stored (fp16 values for fp16 channels)
    const uint16_t* age;    // W*H: ages after the frame
    const float* depth;     // W*H: this frame's depth, in the context's depth mode
    const float* fallback;  // W*H*components, or NULL; read only with fill_prior > 0
    // The deviation gate's state as the frame's pass stored it (this frame's;
    // docs/CONVENTIONS.md, "The deviation gate", "With a spatial fill"): beta
    // and varsigma, W*H each, required for a channel with gate_kappa > 0 (the
    // kappa of the channel's parameters), and the bounds on how far the
    // kernel's fp32 state can be from them (GateState::*_err; NULL: exact).
    const double* gate_beta = nullptr;
    const double* gate_sq = nullptr;
    const double* gate_beta_err = nullptr;
    const double* gate_sq_err = nullptr;
};

struct FillOptions {
    double error_scale = 1.0;  // multiplies the fp32 error margins (as Options::error_scale)
    // Test support: false drops the fade (phi = 1), to check that a test of
    // the kernel would notice a fill that does not fade out.
    bool fade = true;
    // The output image is fp16 (an interop host's fp16 image): the displayed
    // value is rounded to fp16.  Standalone, values are read back from an fp32
    // display image (also for fp16 channels): no rounding.
    bool fp16_output = false;
    // Test support: false leaves the gate's weighing out (every neighbour the
    // fill's other rules count counts), to check that a test of the kernel
    // would notice a fill that ignores the gate.
    bool gate = true;
};

struct FillResult {
    std::vector<double> shown;            // W*H*components: the displayed value as output (fp16 rounded for fp16 channels)
    std::vector<double> exact;            // the same before the fp16 rounding
    std::vector<double> err;              // bound on the fp32 evaluation's error of `exact`
    std::vector<uint8_t> filled;          // W*H: not background and n_p < T (the formula applies)
    std::vector<uint8_t> neighbours;      // W*H: neighbours counted (filled pixels)
    // W*H: the kernel may count another set of neighbours: a neighbour's depth
    // test is within fp32 error of tau, or its gate test is uncertain
    // (gate_near_threshold).
    std::vector<uint8_t> near_threshold;
    // The gate's weighing (channels with gate_kappa > 0), W*H: the neighbours
    // it left out of those the fill's other rules count, and the pixels where
    // a neighbour's test Delta_q^2 <= kappa^2 v_p is within the fp32 error of
    // the kernel's evaluation and of its state (or where the kernel's
    // varsigma_p may be 0 on one side and not on the other while the test
    // could leave a neighbour out).
    std::vector<uint8_t> gate_excluded;
    std::vector<uint8_t> gate_near_threshold;
};

// The displayed values of channel `c` (its fill_age must be > 0).
FillResult spatial_fill(const Params& p, size_t c, const FillInputs& in, const FillOptions& options = {});
FillResult spatial_fill(const rrc_context_desc& ctx, size_t c, const FillInputs& in, const FillOptions& options = {});

}  // namespace rrc_ref

#endif
