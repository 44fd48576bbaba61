#include "gate.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "error_bound.h"
#include "rrc_reference.h"  // fp16_round

namespace rrc_ref {

namespace {

const double kNoCap = 65535.0;  // RRC_MAX_AGE_CAP: "no cap" (docs/CONVENTIONS.md, "The deviation gate")

// Range (max - min) of f(x, y) over the 4x4 texels around the bilinear cell at
// q, clamped: every tap any filter reads, and the cells a q within a small
// error of the nominal one can reach.
template <class F>
double spread_4x4(const BilinearTaps& t, int width, int height, F f) {
    double lo = INFINITY, hi = -INFINITY;
    for (int b = -1; b <= 2; ++b)
        for (int a = -1; a <= 2; ++a) {
            const int x = std::min(std::max(t.x0 + a, 0), width - 1), y = std::min(std::max(t.y0 + b, 0), height - 1);
            const double v = f(x, y);
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    return hi - lo;
}

// N_g = max(1, floor(min(ratio, 65535))).
double cap_of(double ratio) { return std::max(1.0, std::floor(std::min(ratio, kNoCap))); }
// kappa^2 v / beta^2 with v = max(varsigma - beta^2, 0); infinite (no cap)
// where beta^2 is below the fp32 normal range.
double ratio_of(double kappa2, double beta, double sq) {
    const double b2 = beta * beta;
    if (!(b2 >= 0x1p-126)) return INFINITY;
    return kappa2 * std::max(sq - b2, 0.0) / b2;
}

}  // namespace

GateState gate_previous(const std::vector<double>& beta, const std::vector<double>& sq, const std::vector<double>& beta_err,
                        const std::vector<double>& sq_err, int width, int height, double qx, double qy, double q_err) {
    GateState g;
    if (beta.empty() && sq.empty()) return g;  // a state of (0, 0) everywhere
    const BilinearTaps t = bilinear_taps(qx, qy, width, height);
    double abs_b = 0.0, abs_s = 0.0;
    for (int n = 0; n < 4; ++n) {
        if (!(t.w[n] > 0.0)) continue;  // a zero weight reads nothing (a tainted tap's infinite bound included)
        const size_t k = static_cast<size_t>(t.y[n]) * width + t.x[n];
        g.beta += t.w[n] * beta[k];
        g.sq += t.w[n] * sq[k];
        abs_b += t.w[n] * std::fabs(beta[k]);
        abs_s += t.w[n] * std::fabs(sq[k]);
        if (!beta_err.empty()) g.beta_err += t.w[n] * beta_err[k];
        if (!sq_err.empty()) g.sq_err += t.w[n] * sq_err[k];
    }
    // fp32: each weight (1 - f, the product: 3u), its product with the tap
    // and the three additions (4u); the fetch position's error moves the
    // result by at most the state's steepness: 2 x its spread per texel, per axis.
    const auto at = [&](const std::vector<double>& v) { return [&v, width](int x, int y) { return v[static_cast<size_t>(y) * width + x]; }; };
    g.beta_err += 7.0 * kU * abs_b + 4.0 * q_err * spread_4x4(t, width, height, at(beta));
    g.sq_err += 7.0 * kU * abs_s + 4.0 * q_err * spread_4x4(t, width, height, at(sq));
    return g;
}

void resample_error(const Image& history, double qx, double qy, double q_err, double* err) {
    const BilinearTaps t = bilinear_taps(qx, qy, history.width, history.height);
    for (unsigned c = 0; c < history.components; ++c) {
        double largest = 0.0;
        const double spread = spread_4x4(t, history.width, history.height, [&](int x, int y) {
            const double v = history.at(x, y, c);
            largest = std::max(largest, std::fabs(v));
            return v;
        });
        // Up to 16 taps with weights of total magnitude below 1.5 (Catmull-Rom's
        // negative lobes), each formed and summed in fp32: 16u of the largest
        // tap; the position as in gate_previous.
        err[c] = 16.0 * kU * largest + 4.0 * q_err * spread;
    }
}

Deviation gate_deviation(unsigned components, const double* s, const double* h, const double* h_err) {
    Deviation r;
    const unsigned m = std::min(components, 3u);
    double sum = 0.0, magnitude = 0.0, propagated = 0.0;
    for (unsigned k = 0; k < m; ++k) {
        const double diff = s[k] - h[k];
        r.finite = r.finite && std::fabs(diff) <= FLT_MAX;  // fp32 rounds a larger difference to inf
        sum += diff;
        r.finite = r.finite && std::fabs(sum) <= FLT_MAX;
        magnitude += std::fabs(s[k]) + std::fabs(h[k]);
        propagated += h_err[k];
    }
    r.d = sum / m;
    // fp32: each difference and each partial sum rounds (within u of the
    // operands' magnitudes, 3u in all), 1/m and the product 2u more.
    r.err = (propagated + 3.0 * kU * magnitude) / m + 2.0 * kU * std::fabs(r.d);
    if (!r.finite) r.d = NAN;
    return r;
}

GateState gate_stored(const GateState& s) {
    const double kHalfMax = 65504.0;
    GateState out;  // (0, 0) exactly, unless the range test is uncertain
    const double r = std::sqrt(std::max(s.sq, 0.0));
    // r's interval: varsigma within its bound, then the kernel's fp32 sqrt (2u).
    const double r_lo = std::sqrt(std::max(s.sq - s.sq_err, 0.0)) * (1.0 - 2.0 * kU);
    const double r_hi = std::sqrt(s.sq + s.sq_err) * (1.0 + 2.0 * kU);
    const double b_lo = s.beta - s.beta_err, b_hi = s.beta + s.beta_err;
    const bool in_range = std::fabs(s.beta) <= kHalfMax && r <= kHalfMax;
    const bool unbounded = std::isinf(s.beta_err) || std::isinf(s.sq_err);  // the kernel's state may be anything
    const bool surely = std::max(std::fabs(b_lo), std::fabs(b_hi)) <= kHalfMax && r_hi <= kHalfMax;
    const bool surely_not = std::min(std::fabs(b_lo), std::fabs(b_hi)) > kHalfMax || r_lo > kHalfMax;
    if (!unbounded && !surely && !surely_not) {  // the kernel may store (0, 0) or the rounding
        out.beta_err = out.sq_err = INFINITY;
        return out;
    }
    const double r16 = fp16_round(r);
    if (in_range) out.beta = fp16_round(s.beta), out.sq = r16 * r16;
    if (unbounded) out.beta_err = out.sq_err = INFINITY;
    if (unbounded || !in_range) return out;
    out.beta_err = std::max(std::fabs(fp16_round(b_lo) - out.beta), std::fabs(fp16_round(b_hi) - out.beta));
    const double q_lo = fp16_round(r_lo), q_hi = fp16_round(r_hi);
    out.sq_err = std::max(std::fabs(q_lo * q_lo - out.sq), std::fabs(q_hi * q_hi - out.sq));
    return out;
}

Gate gate_update(double kappa, const GateState& prev, const Deviation& dv, unsigned n_prev, double scale) {
    Gate g;
    if (!dv.finite) {  // beta = (1 - a) beta_p + a * inf: not finite, stored (0, 0), no cap
        g.finite = false;
        return g;
    }
    const double a = std::max(1.0 / (n_prev + 1.0), 0.25), d = dv.d;
    const double beta = (1.0 - a) * prev.beta + a * d, sq = (1.0 - a) * prev.sq + a * (d * d);
    // fp32 overflow (d * d, or the blends), and the region where the kernel's
    // fp32 may overflow or not: there its state is unknown.
    const double largest = std::max({d * d, std::fabs(beta), sq});
    g.finite = d * d <= FLT_MAX && std::fabs(beta) <= FLT_MAX && sq <= FLT_MAX;
    const bool near_overflow = largest > FLT_MAX / 4.0;
    if (g.finite) {
        g.state.beta = beta;
        g.state.sq = sq;
        // The previous bounds decay with 1 - a; the deviation's enter with a;
        // fp32: a, 1 - a and the two products and the sum (4u on beta, 5u on
        // varsigma with d * d), and the fp32 store (1u).
        g.state.beta_err = (1.0 - a) * prev.beta_err + a * dv.err +
                           scale * kU * (4.0 * ((1.0 - a) * std::fabs(prev.beta) + a * std::fabs(d)) + std::fabs(beta));
        g.state.sq_err = (1.0 - a) * prev.sq_err + a * (2.0 * std::fabs(d) * dv.err + dv.err * dv.err) +
                         scale * kU * (5.0 * ((1.0 - a) * std::fabs(prev.sq) + a * d * d) + sq);
    }
    if (near_overflow) {
        g.state.beta_err = g.state.sq_err = INFINITY;
        g.age_lo = 1;  // the kernel may cap anywhere, or not at all
        return g;
    }
    if (!g.finite || n_prev < 2) return g;  // no cap
    const double kappa2 = kappa * kappa;
    g.ratio = ratio_of(kappa2, beta, sq);
    g.age = static_cast<unsigned>(std::isinf(g.ratio) ? kNoCap : cap_of(g.ratio));
    // The range: beta and varsigma within their bounds (the ratio falls with
    // |beta| and rises with varsigma), then the formula's own fp32 roundings:
    // beta^2, varsigma - beta^2, kappa^2, the product and the quotient move the
    // ratio by at most 8u (ratio + kappa^2) (kappa^2 varsigma / beta^2 =
    // ratio + kappa^2 is what the roundings act on: the cancellation in
    // varsigma - beta^2 costs absolute, not relative, digits).
    const double b = std::fabs(beta);
    const double r_lo = ratio_of(kappa2, b + g.state.beta_err, sq - g.state.sq_err);
    const double r_hi = ratio_of(kappa2, std::max(b - g.state.beta_err, 0.0), sq + g.state.sq_err);
    const double slack_lo = 8.0 * scale * kU * (r_lo + kappa2), slack_hi = 8.0 * scale * kU * (r_hi + kappa2);
    g.age_lo = static_cast<unsigned>(std::isinf(r_lo) ? kNoCap : cap_of(r_lo - slack_lo));
    g.age_hi = static_cast<unsigned>(std::isinf(r_hi) || std::isnan(r_hi) ? kNoCap : cap_of(r_hi + slack_hi));
    g.age_lo = std::min(g.age_lo, g.age);
    g.age_hi = std::max(g.age_hi, g.age);
    return g;
}

}  // namespace rrc_ref
