#include "view_lobe.h"

#include "params.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace rrc_ref {

bool view_lobe_world_position(const double m[16], double x, double y, double z, double P[3]) {
    const double v[4] = {x, y, z, 1.0};
    double X[4] = {0, 0, 0, 0};
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) X[row] += m[col * 4 + row] * v[col];
    if (X[3] == 0.0) return false;
    for (int k = 0; k < 3; ++k) {
        P[k] = X[k] / X[3];
        if (!std::isfinite(P[k])) return false;
    }
    return true;
}

namespace {

// The angle between a and b from atan2(|a x b|, a . b): accurate for the small
// angles that matter here, where acos of the normalised dot product loses half
// the digits.  0 where either is zero or not finite (no view direction), or
// below the fp32 normal range (the kernel's threshold: no turn).
double view_angle(const glm::dvec3& a, const glm::dvec3& b) {
    const double la = glm::length(a), lb = glm::length(b);
    if (!std::isfinite(la) || !std::isfinite(lb) || !(la > 0.0) || !(lb > 0.0)) return 0.0;
    const double theta = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
    return theta < FLT_MIN ? 0.0 : theta;
}

ViewTurn view_turn_of_eyes(const Params& p, const rrc_frame_desc& frame, int i, int j, double d) {
    ViewTurn t;
    const glm::dmat4 inv = glm::inverse(glm::make_mat4(frame.view_proj));
    const double x = 2.0 * (i + 0.5 + frame.jitter[0]) / p.width - 1.0;
    const double y = 2.0 * (j + 0.5 + frame.jitter[1]) / p.height - 1.0;
    glm::dvec4 c(x, y, d, 1.0);
    if (p.mode == RRC_DEPTH_MODE_LINEAR) {
        const glm::dvec4 row3(inv[0][3], inv[1][3], inv[2][3], inv[3][3]);
        const double a = row3.x * x + row3.y * y + row3.w;
        c = glm::dvec4(x * d, y * d, (1.0 - d * a) / row3.z, d);
    }
    const glm::dvec4 X = inv * c;
    if (X.w == 0.0) return t;
    const glm::dvec3 P = glm::dvec3(X) / X.w;
    const glm::dvec3 C = glm::make_vec3(frame.camera_position), Cp = glm::make_vec3(frame.prev_camera_position);
    const glm::dvec3 a = P - C;
    const double la = glm::length(a);
    t.theta = view_angle(a, P - Cp);
    if (!std::isfinite(la) || !(la > 0.0) || !std::isfinite(glm::length(P - Cp)) || !(glm::length(P - Cp) > 0.0)) return t;
    // The kernel forms a = (Q c).xyz / (Q c).w in fp32, Q = translate(-C) inverse(VP) rounded:
    // each component off by a few ulps of the sum of |products|, relative to |a|; theta
    // ~ |a x d| / |a|^2 moves by that error times |d| / |a|^2, plus a few ulps of itself
    // (atan, length).  A generous constant: an uncertain pixel is only compared loosely.
    const glm::dmat4 Q = glm::dmat4(glm::dvec4(1, 0, 0, 0), glm::dvec4(0, 1, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(-C, 1.0)) * inv;
    double S = 0.0;
    for (int row = 0; row < 3; ++row) {
        double sum = 0.0;
        for (int col = 0; col < 4; ++col) sum += std::fabs(Q[col][row] * c[col]);
        S = std::max(S, sum);
    }
    S /= std::fabs(X.w);
    const double e_a = 64.0 * std::ldexp(1.0, -24) * (S + la);
    t.err = e_a * glm::length(Cp - C) / (la * la) * 4.0 + 64.0 * std::ldexp(1.0, -24) * t.theta;
    return t;
}

}  // namespace

ViewLobe view_lobe_age(double lobe, const double P[3], const double C[3], const double C_prev[3], unsigned n_prev) {
    const glm::dvec3 p = glm::make_vec3(P);
    ViewTurn t;
    t.theta = view_angle(p - glm::make_vec3(C), p - glm::make_vec3(C_prev));
    return view_lobe_cap(lobe, t, n_prev);
}

ViewTurn view_turn(const Params& p, const rrc_frame_desc& frame, int i, int j, double d) {
    // The lighting's turn phi adds to the view's (0 where the view's is undefined); the
    // kernel's fp32 sum rounds once more.
    ViewTurn t = view_turn_of_eyes(p, frame, i, j, d);
    const double phi = frame.lighting_turn;
    t.theta += phi;
    if (phi > 0.0) t.err += 2.0 * std::ldexp(1.0, -24) * t.theta;
    return t;
}

ViewLobe view_lobe_cap(double lobe, const ViewTurn& turn, unsigned n_prev) {
    ViewLobe v;
    v.theta = turn.theta;
    v.age = v.age_lo = v.age_hi = n_prev;
    v.r = std::numeric_limits<double>::infinity();
    auto cap = [&](double theta) {
        if (!(theta >= FLT_MIN)) return n_prev;
        return static_cast<unsigned>(std::min(std::floor(lobe / theta), static_cast<double>(n_prev)));
    };
    if (turn.theta == 0.0) {
        v.age_lo = cap(turn.err);  // an fp32 theta up to err may cap
        return v;
    }
    v.r = lobe / turn.theta;
    v.age = cap(turn.theta);
    v.age_lo = cap(turn.theta + turn.err);
    v.age_hi = cap(turn.theta - turn.err);
    return v;
}

double view_lobe_lambda(double lambda_eff, unsigned n_prev, unsigned n_v) {
    if (n_v >= n_prev) return lambda_eff;
    return std::min(lambda_eff, n_v / (n_v + 1.0));
}

}  // namespace rrc_ref
