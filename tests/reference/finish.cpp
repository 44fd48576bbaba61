#include "finish.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rrc_reference.h"
#include "rrc_kernel_interface.h"  // RRC_ANTILAG_DARKNESS (a constant, written once)

namespace rrc_ref {

namespace {

const double kU32 = 0x1p-24;  // unit roundoff of fp32

size_t index(int width, int x, int y) { return static_cast<size_t>(y) * width + x; }

}  // namespace

bool sample_valid(const ChannelParams& ch, const rrc_channel_input& in, size_t pixel) {
    for (unsigned c = 0; c < ch.components; ++c)
        if (!std::isfinite(in.samples[pixel * ch.components + c])) return false;
    return !ch.confidence || std::isfinite(in.confidence[pixel]);
}

RectifyBox rectify_box(const ChannelParams& ch, const rrc_channel_input& in, int W, int H, int i, int j) {
    RectifyBox b;
    double sum[4] = {0, 0, 0, 0}, sum2[4] = {0, 0, 0, 0}, sum_abs[4] = {0, 0, 0, 0}, max2[4] = {0, 0, 0, 0};
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            // Clamped taps: an edge pixel's repeated taps count each time.
            const int x = std::min(std::max(i + dx, 0), W - 1), y = std::min(std::max(j + dy, 0), H - 1);
            const size_t q = index(W, x, y);
            if (!sample_valid(ch, in, q)) continue;
            ++b.taps;
            for (unsigned c = 0; c < ch.components; ++c) {
                const double s = in.samples[q * ch.components + c];
                sum[c] += s;
                sum2[c] += s * s;
                sum_abs[c] += std::fabs(s);
                max2[c] = std::max(max2[c], s * s);
            }
        }
    }
    if (b.taps == 0) return b;  // cannot happen where rectification applies (the centre is valid)
    const double m = b.taps, gamma = ch.rectify_gamma;
    for (unsigned c = 0; c < ch.components; ++c) {
        const double mu = sum[c] / m, mean2 = sum2[c] / m;
        const double var = std::max(mean2 - mu * mu, 0.0);
        const double sigma = std::sqrt(var);
        b.mu[c] = mu;
        b.sigma[c] = sigma;
        b.lo[c] = mu - gamma * sigma;
        b.hi[c] = mu + gamma * sigma;
        // fp32 error, with a factor ~2 of slack over the first-order bound:
        // the sums of up to 9 terms (8u each), the division, mu^2, the
        // difference; |sqrt(v + d) - sqrt(v)| <= min(sqrt|d|, |d|/sqrt(v)).
        // The largest square bounds the moments about any one tap too (an
        // evaluation about the centre sample, which cancels less).
        const double mu_err = 16.0 * kU32 * (sum_abs[c] / m);
        const double var_err = 64.0 * kU32 * (mean2 + max2[c]);
        double sigma_err = std::sqrt(var_err);
        if (sigma > 0.0) sigma_err = std::min(sigma_err, var_err / sigma);
        b.err[c] = mu_err + gamma * (sigma_err + 2.0 * kU32 * sigma) + 2.0 * kU32 * std::fabs(mu);
        b.mu_err[c] = mu_err + 2.0 * kU32 * std::fabs(mu);
        b.sigma_err[c] = sigma_err + 2.0 * kU32 * sigma;
    }
    return b;
}

void rectify_history(const RectifyBox& b, unsigned components, double* h, double* err) {
    for (unsigned c = 0; c < components; ++c) {
        const double e = b.err[c];
        // Strictly inside the box by more than its error: the kernel's clamp is a no-op too.
        err[c] = (h[c] > b.lo[c] + e && h[c] < b.hi[c] - e) ? 0.0 : e;
        h[c] = std::min(std::max(h[c], b.lo[c]), b.hi[c]);
    }
}

Antilag antilag_age(const ChannelParams& ch, const RectifyBox& b, const double* h, unsigned n_prev) {
    // docs/CONVENTIONS.md, "The lag detector": per component the distance from
    // H to mu +- gamma_a sigma over max(|H|, |mu|) + gamma_a sigma + delta.
    const double ga = ch.antilag_gamma, T = ch.antilag_threshold, delta = RRC_ANTILAG_DARKNESS;
    Antilag a;
    double d_lo = 0.0, d_hi = 0.0;
    for (unsigned k = 0; k < ch.components; ++k) {
        const double gap = std::max(std::fabs(h[k] - b.mu[k]) - ga * b.sigma[k], 0.0);
        const double den = std::max(std::fabs(h[k]), std::fabs(b.mu[k])) + ga * b.sigma[k] + delta;
        const double d = gap / den;
        // The fp32 evaluation's error: the box's (mu, gamma_a sigma), the
        // resampled H's, the roundings of the gap and the quotient.
        const double e_h = 1e-4 * (std::fabs(h[k]) + std::fabs(b.mu[k]) + b.sigma[k]) + 1e-6;
        const double e_box = b.mu_err[k] + ga * b.sigma_err[k] + e_h;
        const double err = (e_box + d * e_box) / den + 8.0 * kU32 * (d + 1.0);
        a.d = std::max(a.d, d);
        d_lo = std::max(d_lo, d - err);
        d_hi = std::max(d_hi, d + err);
    }
    auto conf = [T](double d) { return std::min(std::max(2.0 - 2.0 * d / T, 0.0), 1.0); };
    auto age_at = [n_prev](double c) {
        const double v = std::floor(std::min(std::max(c, 0.0), 1.0) * n_prev);
        return static_cast<unsigned>(std::min(v, static_cast<double>(n_prev)));
    };
    a.c = conf(a.d);
    a.age = age_at(a.c);
    // c strictly inside (0, 1) is a rounded fp32 value; clamped to 0 or 1 it is exact.
    auto widen = [](double c, double by) { return c > 0.0 && c < 1.0 ? c + by : c; };
    a.age_lo = age_at(widen(conf(d_hi), -4.0 * kU32));
    a.age_hi = age_at(widen(conf(d_lo), 4.0 * kU32));
    return a;
}

void gaussian_weights(double t, double g, double w[4]) {
    w[0] = g * (1.0 - t);
    w[1] = (1.0 - 2.0 * g) * (1.0 - t) + g * t;
    w[2] = g * (1.0 - t) + (1.0 - 2.0 * g) * t;
    w[3] = g * t;
}

double resampling_blur(const ChannelParams& ch, double f) {
    // The weights' second moment about the fetch point f, tap by tap.
    if (ch.filter == RRC_HISTORY_FILTER_BILINEAR) return (1.0 - f) * f * f + f * (1.0 - f) * (1.0 - f);
    if (ch.filter == RRC_HISTORY_FILTER_GAUSSIAN) {
        double w[4];
        gaussian_weights(f, ch.blur_g, w);
        double m = 0.0;
        for (int i = 0; i < 4; ++i) m += w[i] * (i - 1 - f) * (i - 1 - f);
        return m;
    }
    return 0.0;  // NEAREST moves, Catmull-Rom reproduces quadratics: no second moment
}

namespace {

// The range of one axis's blur over sample coordinates q +- e.  The fraction
// of q - 0.5 runs from frac(p0) to frac(p1), wrapping through 1 = 0 where the
// floor differs; the moment is concave in f (a parabola peaking at 1/2) and
// equal at f = 0 and f -> 1, so its extremes lie at the ends, at 0 and at 1/2.
void blur_range(const ChannelParams& ch, double q, double e, double& lo, double& hi) {
    const double p0 = q - 0.5 - e, p1 = q - 0.5 + e;
    const double f0 = p0 - std::floor(p0), f1 = p1 - std::floor(p1);
    const double b0 = resampling_blur(ch, f0), b1 = resampling_blur(ch, f1);
    lo = std::min(b0, b1);
    hi = std::max(b0, b1);
    if (std::floor(p0) != std::floor(p1)) {
        lo = std::min(lo, resampling_blur(ch, 0.0));
        if (std::floor(p1) - std::floor(p0) > 1.0 || f0 <= 0.5 || f1 >= 0.5) hi = std::max(hi, resampling_blur(ch, 0.5));
    } else if (f0 <= 0.5 && f1 >= 0.5) {
        hi = std::max(hi, resampling_blur(ch, 0.5));
    }
}

// N = floor(B / b) capped at RRC_MAX_AGE_CAP; a b below the fp32 normal range is no blur.
unsigned blur_cap(double B, double b) {
    if (!(b >= 0x1p-126)) return RRC_MAX_AGE_CAP;
    return static_cast<unsigned>(std::min(std::floor(B / b), static_cast<double>(RRC_MAX_AGE_CAP)));
}

}  // namespace

BlurBound blur_bound_age(const ChannelParams& ch, double qx, double qy, double q_err) {
    BlurBound r;
    const auto frac = [](double q) { return (q - 0.5) - std::floor(q - 0.5); };
    r.b = std::max(resampling_blur(ch, frac(qx)), resampling_blur(ch, frac(qy)));
    r.age = blur_cap(ch.blur_bound, r.b);
    double xlo, xhi, ylo, yhi;
    blur_range(ch, qx, q_err, xlo, xhi);
    blur_range(ch, qy, q_err, ylo, yhi);
    // fp32: b's products and sums, and B / b, each within a relative 2e-6.
    const double slack = 2e-6;
    r.age_lo = blur_cap(ch.blur_bound, std::max(xhi, yhi) * (1.0 + slack));
    r.age_hi = blur_cap(ch.blur_bound, std::max(xlo, ylo) * (1.0 - slack));
    return r;
}

double fill_depth_proxy(rrc_depth_mode mode, double z) {
    switch (mode) {
        case RRC_DEPTH_MODE_STANDARD: return 1.0 / (1.0 - z);
        case RRC_DEPTH_MODE_REVERSED: return 1.0 / z;
        default: return z;
    }
}

namespace {

// The deviation gate's weighing of one filled pixel's neighbours
// (docs/CONVENTIONS.md, "The deviation gate", "With a spatial fill").
struct FillGate {
    bool on = false;         // the reference's varsigma_p > 0: the test applies
    bool maybe = false;      // the kernel's varsigma_p may be on the other side of 0
    double limit = 0.0;      // kappa^2 v_p
    double limit_err = 0.0;  // bound on the kernel's fp32 kappa^2 v_p: its state's and its roundings
};

FillGate fill_gate(const ChannelParams& ch, const FillInputs& in, size_t px, double scale) {
    FillGate g;
    const double beta = in.gate_beta[px], sq = in.gate_sq[px];
    const double beta_err = in.gate_beta_err ? in.gate_beta_err[px] : 0.0, sq_err = in.gate_sq_err ? in.gate_sq_err[px] : 0.0;
    g.on = sq > 0.0;
    // The kernel tests its own varsigma > 0: the sign is certain only where
    // the state's bound keeps it on the reference's side.
    g.maybe = g.on ? !(sq > sq_err) : sq_err > 0.0;
    const double k2 = ch.gate_kappa * ch.gate_kappa;
    const double v = std::max(sq - beta * beta, 0.0);
    g.limit = k2 * v;
    // v = max(varsigma - beta^2, 0) within the state's bounds (error_scale is
    // in them already), and fp32's beta^2, difference, kappa^2 and product
    // (4u, x2 slack).
    const double v_err = sq_err + (2.0 * std::fabs(beta) + beta_err) * beta_err;
    g.limit_err = k2 * v_err + scale * 8.0 * kU32 * k2 * (sq + beta * beta + v);
    return g;
}

// The gate's test of neighbour q: Delta_q = (1/m) sum_{k<m} (v_q,k - v_p,k),
// m = min(components, 3), counted where Delta_q^2 <= kappa^2 v_p.  Sets `near`
// where the kernel's fp32 Delta_q^2 and kappa^2 v_p may fall on the other
// side of each other (or, with g.maybe, where the kernel may leave q out).
bool fill_gate_passes(const FillGate& g, unsigned components, const float* vp, const float* vq, double scale, bool& near) {
    const unsigned m = std::min(components, 3u);
    double sum = 0.0, spread = 0.0;
    for (unsigned k = 0; k < m; ++k) {
        const double d = static_cast<double>(vq[k]) - vp[k];  // exact in double
        sum += d;
        spread += std::fabs(d);
    }
    const double delta = sum / m, lhs = delta * delta;
    const bool pass = lhs <= g.limit;
    near = false;
    // Equal values make Delta = 0 in fp32 too, and 0 <= kappa^2 v_p always.
    if (spread == 0.0 || !std::isfinite(lhs)) return pass;
    // The kernel's Delta: m differences, m - 1 sums and the product with a
    // rounded 1/3, each one rounding of at most the differences' sum (x2
    // slack); then its square.
    const double d_err = scale * 2.0 * (2.0 * m + 1.0) * kU32 * spread / m;
    const double lhs_err = (2.0 * std::fabs(delta) + d_err) * d_err + scale * 2.0 * kU32 * lhs;
    const double margin = lhs_err + g.limit_err;
    if (g.maybe)
        near = !(lhs + margin < g.limit);  // the kernel may leave q out, or not test it at all
    else
        near = std::fabs(lhs - g.limit) <= margin;
    return pass;
}

}  // namespace

FillResult spatial_fill(const Params& p, size_t c, const FillInputs& in, const FillOptions& options) {
    if (c >= p.channels.size()) throw std::invalid_argument("rrc_ref::spatial_fill: no such channel");
    const ChannelParams& ch = p.channels[c];
    if (ch.fill_age == 0) throw std::invalid_argument("rrc_ref::spatial_fill: the channel has no fill");
    if (!in.values || !in.age || !in.depth || (ch.fill_prior > 0.0 && !in.fallback))
        throw std::invalid_argument("rrc_ref::spatial_fill: NULL input");
    // The gate weighs the fill's neighbours by the state the frame's pass stored.
    const bool gated = ch.gate_kappa > 0.0 && options.gate;
    if (ch.gate_kappa > 0.0 && (!in.gate_beta || !in.gate_sq))
        throw std::invalid_argument("rrc_ref::spatial_fill: a gated channel's fill needs the stored gate state");
    const int W = p.width, H = p.height, r = ch.fill_radius;
    const unsigned K = ch.components, T = ch.fill_age;
    const size_t n = static_cast<size_t>(W) * H;
    FillResult res;
    res.shown.assign(n * K, 0.0);
    res.exact.assign(n * K, 0.0);
    res.err.assign(n * K, 0.0);
    res.filled.assign(n, 0);
    res.neighbours.assign(n, 0);
    res.near_threshold.assign(n, 0);
    res.gate_excluded.assign(n, 0);
    res.gate_near_threshold.assign(n, 0);

    auto finite_value = [&](const float* v, size_t px) {
        for (unsigned k = 0; k < K; ++k)
            if (!std::isfinite(v[px * K + k])) return false;
        return true;
    };
    for (int j = 0; j < H; ++j) {
        for (int i = 0; i < W; ++i) {
            const size_t px = index(W, i, j);
            const unsigned np = in.age[px];
            for (unsigned k = 0; k < K; ++k) res.exact[px * K + k] = in.values[px * K + k];
            if (is_background(p, in.depth[px]) || np >= T) continue;
            res.filled[px] = 1;

            const double dp = fill_depth_proxy(p.mode, in.depth[px]);
            const bool valid_p = !is_invalid_depth(p, in.depth[px]);  // an invalid depth takes no neighbour
            const double phi = options.fade ? static_cast<double>(T - np) / T : 1.0;
            // Where varsigma_p = 0 (and the kernel's is 0 too) the fill is as without the gate.
            FillGate gate;
            if (gated) gate = fill_gate(ch, in, px, options.error_scale);
            const bool weigh = gate.on || gate.maybe;
            double num[4] = {0, 0, 0, 0}, num_abs[4] = {0, 0, 0, 0}, wsum = 0.0;
            unsigned terms = 0, excluded = 0;
            for (int b = -r; b <= r; ++b) {
                for (int a = -r; a <= r; ++a) {
                    const int x = i + a, y = j + b;
                    if (!valid_p || (a == 0 && b == 0) || x < 0 || y < 0 || x >= W || y >= H) continue;  // outside taps are skipped
                    const size_t q = index(W, x, y);
                    if (is_background(p, in.depth[q]) || in.age[q] < 1 || !finite_value(in.values, q)) continue;
                    const double dq = fill_depth_proxy(p.mode, in.depth[q]);
                    const double lhs = std::fabs(dq - dp), rhs = ch.fill_tau * dp;
                    // 1/(1 - z) and 1/z in fp32: 2u each; the difference and tau*delta: 1u more.
                    const double margin = options.error_scale * 8.0 * kU32 * (std::fabs(dq) + std::fabs(dp));
                    if (std::fabs(lhs - rhs) <= margin) res.near_threshold[px] = 1;
                    if (!(lhs <= rhs)) continue;
                    if (weigh) {
                        bool near = false;
                        const bool pass = fill_gate_passes(gate, K, in.values + px * K, in.values + q * K, options.error_scale, near);
                        if (near) res.near_threshold[px] = res.gate_near_threshold[px] = 1;
                        if (gate.on && !pass) {
                            ++excluded;
                            continue;
                        }
                    }
                    const double w = std::min<unsigned>(in.age[q], T);  // w_q = min(n_q, T)
                    wsum += w;
                    ++terms;
                    for (unsigned k = 0; k < K; ++k) {
                        num[k] += w * in.values[q * K + k];
                        num_abs[k] += w * std::fabs(in.values[q * K + k]);
                    }
                }
            }
            res.neighbours[px] = static_cast<uint8_t>(std::min(terms, 255u));
            res.gate_excluded[px] = static_cast<uint8_t>(std::min(excluded, 255u));
            double prior = 0.0;
            if (ch.fill_prior > 0.0 && finite_value(in.fallback, px)) {
                prior = ch.fill_prior;
                ++terms;
                for (unsigned k = 0; k < K; ++k) {
                    num[k] += prior * in.fallback[px * K + k];
                    num_abs[k] += prior * std::fabs(in.fallback[px * K + k]);
                }
            }
            const double den = np + phi * (wsum + prior);
            if (den == 0.0) continue;  // no sample, no neighbour, no fallback: v_p
            for (unsigned k = 0; k < K; ++k) {
                const double v = in.values[px * K + k];
                const double shown = (np * v + phi * num[k]) / den;
                res.exact[px * K + k] = shown;
                // fp32: the sums (one rounding per term), phi, the products, the division; x2 slack.
                const double magnitude = (np * std::fabs(v) + phi * num_abs[k]) / den;
                res.err[px * K + k] = options.error_scale * 2.0 * (terms + 6) * kU32 * (magnitude + std::fabs(shown));
            }
        }
    }
    for (size_t e = 0; e < n * K; ++e) res.shown[e] = options.fp16_output ? fp16_round(res.exact[e]) : res.exact[e];
    return res;
}

FillResult spatial_fill(const rrc_context_desc& ctx, size_t c, const FillInputs& in, const FillOptions& options) {
    return spatial_fill(resolve(ctx), c, in, options);
}

}  // namespace rrc_ref
