#include "view_lobe.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

ViewLobe view_lobe_age(double lobe, const double P[3], const double C[3], const double C_prev[3], unsigned n_prev) {
    ViewLobe v;
    v.age = n_prev;
    v.r = std::numeric_limits<double>::infinity();
    double a[3], b[3];
    for (int k = 0; k < 3; ++k) a[k] = P[k] - C[k], b[k] = P[k] - C_prev[k];
    const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    if (!(la > 0.0) || !(lb > 0.0)) return v;
    // The angle from atan2(|a x b|, a . b): accurate for the small angles that
    // matter here, where acos of the normalised dot product loses half the digits.
    const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
    const double cross = std::sqrt(cx * cx + cy * cy + cz * cz), dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    v.theta = std::atan2(cross, dot);
    if (v.theta == 0.0) return v;
    v.r = lobe / v.theta;
    v.age = static_cast<unsigned>(std::min(std::floor(v.r), static_cast<double>(n_prev)));
    return v;
}

double view_lobe_lambda(double lambda_eff, unsigned n_prev, unsigned n_v) {
    if (n_v >= n_prev) return lambda_eff;
    return std::min(lambda_eff, n_v / (n_v + 1.0));
}

}  // namespace rrc_ref
