#include "hit_test.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "fetch.h"
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

}  // namespace

HitTest hit_test(const Params& p, const std::vector<float>& prev_depth, const float prev_jitter[2], const Reprojected& r, double scale) {
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
    double ad = std::fabs(diff.v), dd = diff.err * scale;

    Decision within;
    within.value = ad <= eps.value;  // NaN fails, as in the kernel
    within.sure = std::isnan(ad) || ad + dd < eps.lo || ad - dd > eps.hi;
    // A depth beyond fp32 range is inf in the kernel, where inf <= inf may pass.
    if (std::fabs(r.e.v) > FLT_MAX || std::fabs(fetched.v) > FLT_MAX) within.sure = false;

    t.hit = geometry && f.no_background && within;
    t.fetched = fetched.v;
    t.diff = diff.v;
    t.eps = eps.value;
    t.diff_err = dd;
    return t;
}

}  // namespace rrc_ref
