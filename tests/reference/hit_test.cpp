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
// a2, a, c, b, b2: the curvature estimate (the centre's second difference, or
// at a step of its own the smooth side's) less its noise, the slope, whether
// the axis is beside a step and that step's size.  The kernel evaluates them in fp32: its
// one-sided differences and their difference may be off by about 2 ulp of
// the largest tap, so a comparison within that margin may go either way: the
// curvature is a range over every decision the kernel may take, and
// "beside" says which of its values are possible.
struct Range {
    double value, lo, hi;
};
struct Flag {
    bool value, may_be_true, may_be_false;
};
struct Axis {
    Range curvature, slope;
    Flag beside;
    Range step;  // beside a step: the larger |n| of the neighbours of the other sign (the borrow limit's measure)
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
    Axis r{{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {false, false, true}, {0.0, 0.0, 0.0}};
    if (!std::isfinite(s) || !std::isfinite(sm) || !std::isfinite(sp)) return r;
    const double slope = edge ? std::max(std::fabs(dp), std::fabs(dm)) : std::min(std::fabs(dp), std::fabs(dm));
    r.slope = {slope, std::max(slope - err, 0.0), slope + err};
    if (edge) return r;  // no second difference on the image's first and last column/row

    // Each test in three readings: d = +1 the kernel surely passes it (every
    // magnitude off by err against it), 0 as in double, -1 it may pass.
    const double as = std::fabs(s);
    auto opposite = [&](double n, int d) {  // n of the other sign, at least STEP_RATIO of s
        const double e = d * err;
        const bool sign = d > 0   ? (n * s < 0.0 && std::fabs(n) > err && as > err)
                          : d < 0 ? (n * s < 0.0 || std::fabs(n) <= err || as <= err)
                                  : n * s < 0.0;
        return sign && std::fabs(n) - e >= RRC_ADAPTIVE_STEP_RATIO * (as + e);
    };
    // and s, or the one-sided difference towards n, at least STEP_OWN of n: a step of its own
    auto own = [&](double n, double towards, int d) {
        const double e = d * err;
        return opposite(n, d) && std::max(as, std::fabs(towards)) - e >= RRC_ADAPTIVE_STEP_OWN * (std::fabs(n) + e);
    };
    // The smooth side: a neighbour that is not "opposite" and at most SMOOTH_SIDE of s.
    auto side_ok = [&](double n, int d) {
        const double e = d * err;
        return !opposite(n, -d) && std::fabs(n) + e <= RRC_ADAPTIVE_SMOOTH_SIDE * (as - e);
    };
    auto beside = [&](int d) { return (opposite(sm, d) || opposite(sp, d)) && as - d * err > noise; };
    auto is_own = [&](int d) { return own(sm, dm, d) || own(sp, dp, d); };
    r.beside = {beside(0), beside(-1), !beside(1)};
    auto step_height = [&](int d) {  // d = +1 its least, -1 its most
        double h = 0.0;
        for (double n : {sm, sp})
            if (opposite(n, d)) h = std::max(h, std::fabs(n) - d * err);
        return std::max(h, 0.0);
    };
    r.step = {step_height(0), step_height(1), step_height(-1)};

    const double centre = std::max(as - noise, 0.0), centre_lo = std::max(as - noise - err, 0.0),
                 centre_hi = std::max(as - noise + err, 0.0);
    auto side = [&](int d) {  // the smooth side's estimate, before the noise: d = +1 its least, -1 its most, 0 as in double
        double v = 0.0;
        for (double n : {sm, sp})
            if (side_ok(n, d)) v = std::max(v, std::fabs(n) - d * err);
        return std::max(v, 0.0);
    };
    const double side_value = std::max(side(0) - noise, 0.0), side_lo = std::max(side(1) - noise, 0.0),
                 side_hi = std::max(side(-1) - noise, 0.0);
    const bool own_value = is_own(0), own_maybe = is_own(-1), own_sure = is_own(1);
    r.curvature.value = own_value ? side_value : centre;
    r.curvature.lo = own_sure ? side_lo : own_maybe ? std::min(side_lo, centre_lo) : centre_lo;
    r.curvature.hi = own_sure ? side_hi : own_maybe ? std::max(side_hi, centre_hi) : centre_hi;
    return r;
}

// The two axes' curvature as one estimate (docs/CONVENTIONS.md, "The ADAPTIVE
// test"): an axis beside a step borrows the other's only up to BORROW of that
// step, both beside steps give 0; over every combination of decisions the
// kernel may reach.
Range combined_curvature(const Axis& x, const Axis& y) {
    // `s` beside a step, `o` the other axis, not: max(s, o if o <= BORROW * step).
    auto beside_one = [](const Axis& s, const Axis& o) {
        const double k = RRC_ADAPTIVE_BORROW;
        const bool value = o.curvature.value <= k * s.step.value, sure = o.curvature.hi <= k * s.step.lo,
                   maybe = o.curvature.lo <= k * s.step.hi;
        return Range{std::max(s.curvature.value, value ? o.curvature.value : 0.0), std::max(s.curvature.lo, sure ? o.curvature.lo : 0.0),
                     std::max(s.curvature.hi, maybe ? o.curvature.hi : 0.0)};
    };
    auto pick = [&](bool bx, bool by) {
        if (bx && by) return Range{0.0, 0.0, 0.0};
        if (bx) return beside_one(x, y);
        if (by) return beside_one(y, x);
        return Range{std::max(x.curvature.value, y.curvature.value), std::max(x.curvature.lo, y.curvature.lo),
                     std::max(x.curvature.hi, y.curvature.hi)};
    };
    Range c{pick(x.beside.value, y.beside.value).value, INFINITY, -INFINITY};
    for (bool bx : {false, true})
        for (bool by : {false, true}) {
            if (!(bx ? x.beside.may_be_true : x.beside.may_be_false) || !(by ? y.beside.may_be_true : y.beside.may_be_false)) continue;
            const Range r = pick(bx, by);
            c.lo = std::min(c.lo, r.lo);
            c.hi = std::max(c.hi, r.hi);
        }
    return c;
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
    const Range c = combined_curvature(ax, ay);
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
