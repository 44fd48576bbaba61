// The deviation gate (docs/CONVENTIONS.md, "The deviation gate"): the running
// mean beta and mean square varsigma of the deviation d = sample - history,
// and the age cap N_g = max(1, floor(kappa^2 v / beta^2)) they give.
// Re-derived in double from that section, pinned by hand-computed self-tests
// (selftest_gate.cpp); nothing here is shared with compute/ or plugin/.
//
// The kernel stores (beta, varsigma) as fp16 (beta, sqrt(varsigma)) and never
// hands them back, so a test carries the reference's own state, rounded the
// same way (gate_stored), from frame to frame (rrc_reference.h,
// carry_gate_state).  The two states then differ by the kernel's fp32
// roundings where they straddle an fp16 rounding: each state value
// carries here a bound on that difference (GateState::*_err), and the cap the
// range of ages it allows.  Why a propagated bound and not a fixed relative
// margin on kappa^2 v / beta^2: on a clean input d is the history's small
// bias, so the kernel's fp32 history (a few 1e-7 of its value) is a relative
// 1e-4 or more of d, and a biased history makes varsigma - beta^2 cancel:
// the ratio's error is (ratio + kappa^2) times the relative errors of
// varsigma and beta^2, which no one margin fits on every pixel.  The bounds
// are per-operation worst cases (error_bound.h's model) and decay with the
// state (1 - a <= 3/4 a frame).  Measured on lavapipe
// (tests/kernels/gate_reference_test.cpp): 452 of 9747 capped ages flagged on
// the clean pan, none of which the kernel actually took differently.
#ifndef RRC_REFERENCE_GATE_H
#define RRC_REFERENCE_GATE_H

#include <cmath>
#include <vector>

#include "fetch.h"

namespace rrc_ref {

// A pixel's gate state, with bounds on how far the kernel's fp32 state can be
// from it (infinite where the kernel may have taken another case of the table).
struct GateState {
    double beta = 0.0, sq = 0.0;          // beta, varsigma
    double beta_err = 0.0, sq_err = 0.0;  // bounds on |kernel - reference|
};

// The previous state at q (the previous frame's sample coordinate, known
// within q_err texels): the four bilinear taps and weights of
// docs/CONVENTIONS.md, "Previous depth fetch and the hit test", whatever the
// channel's filter.  Each array W*H, or empty (all zero); errors may be empty.
GateState gate_previous(const std::vector<double>& beta, const std::vector<double>& sq, const std::vector<double>& beta_err,
                        const std::vector<double>& sq_err, int width, int height, double qx, double qy, double q_err);

// A bound on how far the kernel's resampled history (the channel's filter in
// fp32 at its fp32 position) can be from resample()'s, per component: the
// filter's roundings, and the history's steepness around q times q_err.
void resample_error(const Image& history, double qx, double qy, double q_err, double* err);

struct Deviation {
    double d = 0.0;
    double err = 0.0;    // bound on the kernel's fp32 d
    bool finite = true;  // no fp32 overflow in the differences or their sum
};

// d = (1/m) sum_{k<m} (s_k - h_k), m = min(components, 3); h_err the
// resampled history's bounds (resample_error).
Deviation gate_deviation(unsigned components, const double* s, const double* h, const double* h_err);

struct Gate {
    GateState state;          // stored: (beta, varsigma), or (0, 0) where not finite
    bool finite = true;       // beta and varsigma finite in fp32 (else the state is (0, 0) and nothing is capped)
    double ratio = INFINITY;  // kappa^2 v / beta^2 (infinite where beta^2 < 2^-126 or n_prev < 2)
    unsigned age = 65535;     // N_g (65535: no cap)
    // The caps the kernel's fp32 state and arithmetic can give: N_g over the
    // state within its bounds, and the ratio within 8 fp32 roundings of
    // (ratio + kappa^2).  age_lo <= age <= age_hi.
    unsigned age_lo = 65535, age_hi = 65535;
};

// The state as the kernel stores it: beta and r = sqrt(varsigma) rounded to
// the nearest fp16 (ties to even), varsigma = r^2; (0, 0) where |beta| or r
// exceeds 65504 (docs/CONVENTIONS.md, "The deviation gate").  The bounds: the
// kernel's value lies within the bound of the reference's, so its rounding
// lies between the roundings of that interval's ends (and the kernel's fp32
// sqrt within 2u of the root): the bound becomes the largest distance from
// the reference's rounding to theirs, 0 where the interval rounds to one value.
GateState gate_stored(const GateState& s);

// One blend's update (a hit, a valid sample, n_prev >= 1) from the previous
// state at the pixel and the deviation.  error_scale multiplies the fp32
// rounding terms (as Options::error_scale).
Gate gate_update(double kappa, const GateState& prev, const Deviation& d, unsigned n_prev, double error_scale = 1.0);

}  // namespace rrc_ref

#endif
