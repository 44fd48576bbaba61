// A double value carried together with a first-order bound on how far the
// fp32 kernel's value of the same expression can be from it.
//
// Model (the margin rule of the reference): each fp32 arithmetic operation
// rounds its result r with an error of at most u*|r|, u = 2^-24, and errors of
// the operands propagate to first order (|d(a*b)| <= |a| db + |b| da, ...).
// Inputs the kernel reads as floats are exact (err 0); values formed on the
// host in double and applied in fp32 (the CAMERA matrices) enter with u*|v|.
// A result below the smallest normal gets FLT_MIN added (denormals may be
// flushed).  fp32 overflow keeps the relative bound: the kernel's inf has the
// value's sign, which is all the range tests need; the epsilon test checks for
// overflow itself (hit_test.cpp).  This is a worst-case bound per operation, not an estimate: it is
// as tight as the values themselves allow and needs no tuning per scene.
#ifndef RRC_REFERENCE_ERROR_BOUND_H
#define RRC_REFERENCE_ERROR_BOUND_H

#include <cfloat>
#include <cmath>
#include <limits>

namespace rrc_ref {

constexpr double kU = 0x1p-24;  // unit roundoff of fp32

struct Bounded {
    double v = 0.0;
    double err = 0.0;
};

// Adds the rounding of the operation that produced v.
inline Bounded rounded(double v, double propagated) {
    double a = std::fabs(v);
    double err = propagated + kU * a;
    if (a < FLT_MIN) err += FLT_MIN;
    if (!(err <= DBL_MAX)) err = std::numeric_limits<double>::infinity();  // NaN too
    return {v, err};
}

inline Bounded exact(double v) { return {v, 0.0}; }
// A double formed on the host and uploaded as fp32.
inline Bounded as_f32(double v) { return rounded(v, 0.0); }

inline Bounded operator+(Bounded a, Bounded b) { return rounded(a.v + b.v, a.err + b.err); }
inline Bounded operator-(Bounded a, Bounded b) { return rounded(a.v - b.v, a.err + b.err); }
inline Bounded operator*(Bounded a, Bounded b) { return rounded(a.v * b.v, std::fabs(a.v) * b.err + std::fabs(b.v) * a.err); }
inline Bounded operator/(Bounded a, Bounded b) {
    double q = a.v / b.v;
    return rounded(q, (a.err + std::fabs(q) * b.err) / std::fabs(b.v));
}

// A comparison decided on exact values, and whether the kernel's fp32 values
// (within the bounds above) are certain to decide it the same way.
struct Decision {
    bool value = false;
    bool sure = true;
};

// Conjunction: surely false as soon as one operand is surely false.
inline Decision operator&&(Decision a, Decision b) {
    bool surely_false = (!a.value && a.sure) || (!b.value && b.sure);
    return {a.value && b.value, surely_false || (a.sure && b.sure)};
}

// x > 0 for x known within +-err.
inline Decision positive(double x, double err) {
    if (std::isnan(x)) return {false, true};
    return {x > 0.0, x - err > 0.0 || x + err <= 0.0};
}

// 0 <= x <= 1 for x known within +-err.
inline Decision in_unit(double x, double err) {
    if (std::isnan(x)) return {false, true};
    bool inside = x >= 0.0 && x <= 1.0;
    bool surely_inside = x - err >= 0.0 && x + err <= 1.0;
    bool surely_outside = x + err < 0.0 || x - err > 1.0;
    return {inside, surely_inside || surely_outside};
}

}  // namespace rrc_ref

#endif
