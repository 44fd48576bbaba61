// Analytic surface patterns (see shading.h).
#include "scenes/shading.h"

#include <algorithm>
#include <cmath>

namespace rrc_scene {
namespace {

constexpr double kTwoPi = 6.28318530717958647692;

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// A blurred square wave of the given period: 1 on half the period, 0 on the other.
double stripe(double u, double period, double phase) { return smoothstep(-0.6, 0.6, std::sin(kTwoPi * (u / period + phase))); }

// Soft exclusive-or: maps [0,1]^2 to [0,1], equals XOR on {0,1}.
double sxor(double a, double b) { return a + b - 2.0 * a * b; }

// Checker period per object (world units): a few pixels at 96x64.
double checker_period(int32_t id) {
    switch (id) {
        case 0: return 1.5;  // ground
        case 4:
        case 5: return 0.35;  // spheres
        default: return 0.6;  // boxes
    }
}

double checker(int32_t id, const glm::dvec3& p, double period) {
    // Phases keep faces of boxes and the ground plane off the pattern's zero crossings.
    const double ph = 0.25 + 0.13 * id;
    return sxor(sxor(stripe(p.x, period, ph), stripe(p.y, period, ph + 0.05)), stripe(p.z, period, ph + 0.1));
}

}  // namespace

double shade1(int32_t id, const glm::dvec3& p) { return checker(id, p, checker_period(id)); }

glm::dvec4 shade4(int32_t id, const glm::dvec3& p) {
    const double k = static_cast<double>(id);
    return glm::dvec4(0.5 + 0.5 * std::sin(kTwoPi * (p.x / 0.9 + 0.3 * p.y) + k),
                      0.5 + 0.5 * std::cos(kTwoPi * (p.z / 1.1 - 0.2 * p.x) + 0.5 * k),
                      0.5 + 0.5 * std::sin(kTwoPi * (p.y / 0.7 + p.z / 1.3) + 0.7 * k), checker(id, p, 2.0 * checker_period(id)));
}

}  // namespace rrc_scene
