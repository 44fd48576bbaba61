// fp16 rounding of stored history values (CONVENTIONS: clamp to +-65504,
// round to nearest, ties to even), done on the double value with exact
// power-of-two scalings so it does not depend on the FPU rounding mode.
#include <cmath>

#include "rrc_reference.h"

namespace rrc_ref {

namespace {

// Round x >= 0 to the nearest integer, ties to even.
double round_half_even(double x) {
    double r = std::floor(x);
    double frac = x - r;  // exact: x < 2^53 here
    if (frac > 0.5) return r + 1.0;
    if (frac < 0.5) return r;
    return std::fmod(r, 2.0) == 0.0 ? r : r + 1.0;
}

}  // namespace

double fp16_round(double v) {
    if (std::isnan(v)) return v;
    double a = std::fabs(v);
    if (a >= 65504.0) return std::copysign(65504.0, v);
    // fp16 spacing: 2^-24 for subnormals (a < 2^-14), else 2^(exponent - 10).
    int exponent = a < 0x1p-14 ? -14 : std::ilogb(a);
    double spacing = std::ldexp(1.0, exponent - 10);
    double r = round_half_even(a / spacing) * spacing;  // may carry into the next binade: fine
    return std::copysign(r, v);
}

}  // namespace rrc_ref
