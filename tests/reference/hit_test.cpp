#include "hit_test.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "fetch.h"
#include "rrc_kernel_interface.h"  // RRC_ADAPTIVE_* (docs/CONVENTIONS.md writes the same constants)
#include "rrc_reference.h"

namespace rrc_ref {

namespace {

struct EpsRange {
    double value, lo, hi;  // exact tolerance, and its range over the kernel's e
};

EpsRange epsilon_range(const Params& p, Bounded e, double scale) {
    double de = e.err * scale, v = epsilon_at(p, e.v);
    if (p.relative_test()) {
        // tau * e; the kernel's tau may be the fp32 rounding of the default 0.01.
        double d = p.tau * de + 2.0 * kU * std::fabs(v) * scale;
        return {v, v - d, v + d};
    }
    if (p.epsilon > 0.0) return {v, v, v};  // the host's float, used as is
    if (p.format != RRC_DEPTH_FORMAT_FLOAT32) {
        double d = kU * v * scale;  // scale / 65535 rounded once
        return {v, v - d, v + d};
    }
    // scale * ulp(e): ulp is non-decreasing in |e|.
    double a = std::fabs(e.v);
    return {v, p.epsilon_scale * ulp_fp32(std::max(a - de, 0.0)), p.epsilon_scale * ulp_fp32(a + de)};
}

// docs/CONVENTIONS.md "The ADAPTIVE test", one axis at the current depth
// a, c, b: the second difference where it is curvature, less its noise, and
// the slope.  The kernel evaluates them in fp32: its one-sided differences
// and their difference may be off by about 2 ulp of the largest tap, so a
// step test within that margin, or a value near the noise floor, is a range.
struct Range {
    double value, lo, hi;
};
struct Axis {
    Range curvature, slope;
};

Axis axis(const Params& p, double a2, double a, double c, double b, double b2, bool edge, double scale) {
    const double dp = b - c, dm = c - a, s = dp - dm;     // exact in double
    const double sm = dm - (a - a2), sp = (b2 - b) - dp;  // the neighbours' second differences
    const double top = std::max(std::max(std::fabs(a), std::fabs(b)), std::fabs(c));
    const double step = p.format == RRC_DEPTH_FORMAT_UNORM16   ? 1.0 / 65535.0
                        : p.format == RRC_DEPTH_FORMAT_UNORM24 ? 1.0 / 16777215.0
                                                               : 0.0;
    const double noise = RRC_ADAPTIVE_NOISE_ULPS * ulp_fp32(top) + RRC_ADAPTIVE_NOISE_STEPS * step;
    // LINEAR's taps are fp32 reciprocals in the kernel: 2 ulp more.
    const double err =
        (p.mode == RRC_DEPTH_MODE_LINEAR ? 4.0 : 2.0) * ulp_fp32(std::max(top, std::max(std::fabs(a2), std::fabs(b2)))) * scale;
    Axis r{{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    if (!std::isfinite(s) || !std::isfinite(sm) || !std::isfinite(sp)) return r;
    const double slope = edge ? std::max(std::fabs(dp), std::fabs(dm)) : std::min(std::fabs(dp), std::fabs(dm));
    r.slope = {slope, std::max(slope - err, 0.0), slope + err};
    // A step: a neighbour's second difference has the other sign and at least
    // STEP_RATIO of its size (+h, -h: a step's signature; curvature and creases keep one sign).
    auto is_step = [&](double e) {
        const double as = std::fabs(s) + e;
        auto opposite = [&](double n) { return n * s < 0.0 && std::fabs(n) - e >= RRC_ADAPTIVE_STEP_RATIO * as; };
        return opposite(sm) || opposite(sp);
    };
    const bool step_sure = is_step(err), step_nominal = is_step(0.0), step_maybe = is_step(-err);
    const double smooth = std::max(std::fabs(s) - noise, 0.0), hi = std::max(std::fabs(s) - noise + err, 0.0);
    if (edge) return r;  // no second difference on the image's first and last column/row
    if (!step_maybe)
        r.curvature = {smooth, std::max(std::fabs(s) - noise - err, 0.0), hi};  // surely curvature
    else if (!step_sure)
        r.curvature = {step_nominal ? 0.0 : smooth, 0.0, hi};  // the kernel may call it either
    return r;                                                  // else surely a step: 0
}

// The ADAPTIVE test's widening at the current pixel: min(cap, GAIN * (residual + edge term)).
Range adaptive_widening(const Params& p, const CurrentPixel& cur, Bounded qx, Bounded qy, Bounded e, double scale) {
    const int W = p.width, H = p.height, i = cur.i, j = cur.j;
    // The interpolated quantity: z, or 1/d for LINEAR (as the fetch).
    auto z = [&](int x, int y) {
        const double v = cur.depth[(size_t)std::min(std::max(y, 0), H - 1) * W + std::min(std::max(x, 0), W - 1)];
        return p.mode == RRC_DEPTH_MODE_LINEAR ? 1.0 / v : v;
    };
    const Axis ax = axis(p, z(i - 2, j), z(i - 1, j), z(i, j), z(i + 1, j), z(i + 2, j), i == 0 || i == W - 1, scale);
    const Axis ay = axis(p, z(i, j - 2), z(i, j - 1), z(i, j), z(i, j + 1), z(i, j + 2), j == 0 || j == H - 1, scale);
    const Range c{std::max(ax.curvature.value, ay.curvature.value), std::max(ax.curvature.lo, ay.curvature.lo),
                  std::max(ax.curvature.hi, ay.curvature.hi)};
    // f (1 - f) of the fetch's fractions and the overhang beyond the outermost
    // texel centres; the kernel's are off by up to q's error.
    auto b = [&](Bounded q) {
        const double f = (q.v - 0.5) - std::floor(q.v - 0.5), v = f * (1.0 - f), d = q.err * scale;
        return Range{v, std::max(v - d, 0.0), std::min(v + d, 0.25)};
    };
    auto over = [&](Bounded q, int size) {
        const double v = std::max(std::max(0.5 - q.v, q.v - 0.5 - (size - 1)), 0.0), d = q.err * scale;
        return Range{v, std::max(v - d, 0.0), v + d};
    };
    const Range bx = b(qx), by = b(qy), ox = over(qx, W), oy = over(qy, H);
    const double gain = RRC_ADAPTIVE_GAIN, rel = 8.0 * kU * scale;  // fp32 products and sums
    // The kernel's own fp32 error of q times the slope.
    const double pos = RRC_ADAPTIVE_POSITION_ULPS * 0x1p-24, px = pos * W, py = pos * H;
    const double w = gain * ((bx.value + by.value) * c.value + ox.value * ax.slope.value + oy.value * ay.slope.value) +
                     px * ax.slope.value + py * ay.slope.value;
    const double w_lo =
        (gain * ((bx.lo + by.lo) * c.lo + ox.lo * ax.slope.lo + oy.lo * ay.slope.lo) + px * ax.slope.lo + py * ay.slope.lo) * (1.0 - rel);
    const double w_hi =
        (gain * ((bx.hi + by.hi) * c.hi + ox.hi * ax.slope.hi + oy.hi * ay.slope.hi) + px * ax.slope.hi + py * ay.slope.hi) * (1.0 + rel);
    if (p.mode == RRC_DEPTH_MODE_LINEAR) {  // from 1/d back to d: |dd| = d^2 |d(1/d)|
        const double e2 = e.v * e.v, de2 = 2.0 * std::fabs(e.v) * e.err * scale;
        const double cap = RRC_ADAPTIVE_CAP * std::fabs(e.v), dcap = RRC_ADAPTIVE_CAP * (e.err * scale) + rel * cap;
        return {std::min(w * e2, cap), std::min(w_lo * std::max(e2 - de2, 0.0) * (1.0 - rel), cap - dcap),
                std::min(w_hi * (e2 + de2) * (1.0 + rel), cap + dcap)};
    }
    const double z_inf = p.mode == RRC_DEPTH_MODE_STANDARD ? 1.0 : 0.0;
    const double cap = RRC_ADAPTIVE_CAP * std::fabs(e.v - z_inf), dcap = RRC_ADAPTIVE_CAP * (e.err * scale) + rel * cap;
    return {std::min(w, cap), std::min(w_lo, cap - dcap), std::min(w_hi, cap + dcap)};
}

}  // namespace

HitTest hit_test(const Params& p, const std::vector<float>& prev_depth, const float prev_jitter[2], const Reprojected& r,
                 const CurrentPixel& cur, double scale) {
    HitTest t;
    Decision geometry = positive(r.w.v, r.w.err * scale) && in_unit(r.uv_x.v, r.uv_x.err * scale) && in_unit(r.uv_y.v, r.uv_y.err * scale);
    t.qx = r.uv_x * exact(p.width) - exact(prev_jitter[0]);
    t.qy = r.uv_y * exact(p.height) - exact(prev_jitter[1]);
    if (!std::isfinite(t.qx.v) || !std::isfinite(t.qy.v)) {
        t.hit = geometry && Decision{false, true};
        return t;
    }

    DepthFetch f = fetch_depth(p, prev_depth, t.qx, t.qy, scale);
    Bounded fetched = p.linearise() ? linearise(p, f.value) : f.value;
    Bounded diff = fetched - r.e;
    EpsRange eps = epsilon_range(p, r.e, scale);
    if (p.adaptive && !p.relative_test()) {  // the fp32 noise floor of an NDC test (UNORM24 near z = 1: ulp ~ step)
        const double a = std::fabs(r.e.v), de = r.e.err * scale, f = RRC_ADAPTIVE_FLOOR_ULPS;
        eps = {std::max(eps.value, f * ulp_fp32(a)), std::max(eps.lo, f * ulp_fp32(std::max(a - de, 0.0))),
               std::max(eps.hi, f * ulp_fp32(a + de))};
    }
    if (p.adaptive) {
        const Range w = adaptive_widening(p, cur, t.qx, t.qy, r.e, scale);
        const double c = r.camera_err, dc = 8.0 * kU * c * scale;  // CAMERA: the allowance for e's own fp32 error
        const double add = kU * (eps.hi + w.hi + c) * scale;       // the fp32 sums
        eps = {eps.value + w.value + c, eps.lo + w.lo + c - dc - add, eps.hi + w.hi + c + dc + add};
    }
    double ad = std::fabs(diff.v), dd = diff.err * scale;

    Decision within;
    within.value = ad <= eps.value;  // NaN fails, as in the kernel
    within.sure = std::isnan(ad) || ad + dd < eps.lo || ad - dd > eps.hi;
    // A depth beyond fp32 range is inf in the kernel, where inf <= inf may pass.
    if (std::fabs(r.e.v) > FLT_MAX || std::fabs(fetched.v) > FLT_MAX) within.sure = false;

    Decision same_object{true, true};
    if (p.object_id)
        same_object = taps_hold_id(*cur.prev_ids, p.width, p.height, t.qx, t.qy, cur.object_id[(size_t)cur.j * p.width + cur.i], scale);
    t.hit = geometry && f.no_background && same_object && within;
    t.fetched = fetched.v;
    t.diff = diff.v;
    t.eps = eps.value;
    t.diff_err = dd;
    return t;
}

}  // namespace rrc_ref
