// Placement, motion, ray intersection and surface distance of the scene objects.
#include "scenes/objects.h"

#include <algorithm>
#include <cmath>

namespace rrc_scene {
namespace {

// Layout (world units): camera orbits at radius ~12 around the origin.  The
// moving sphere floats between the camera and the boxes so it occludes and
// disoccludes them; it never touches another object (its path keeps >= 0.4
// clearance), so all contacts are the static ones below.
const ObjectShape kShapes[OBJECT_COUNT] = {
    {Shape::Plane, {30.0, 0.0, 30.0}, 0.0},  // ground
    {Shape::Box, {1.0, 1.0, 1.0}, 0.0},      // large box
    {Shape::Box, {0.75, 0.75, 1.5}, 0.0},    // long box
    {Shape::Box, {0.8, 0.2, 0.8}, 0.0},      // floating box
    {Shape::Sphere, {0.0, 0.0, 0.0}, 0.9},   // resting sphere
    {Shape::Sphere, {0.0, 0.0, 0.0}, 0.7},   // moving sphere
};

const glm::dvec3 kStaticPositions[OBJECT_COUNT] = {
    {0.0, 0.0, 0.0},   {-2.5, 1.0, -1.5},  // bottom face on y = 0
    {2.0, 0.75, -2.5},                     // bottom face on y = 0
    {3.0, 2.2, 0.5},                       // y in [2.0, 2.4], z in [-0.3, 1.3]
    {-3.0, 0.9, 2.0},                      // touches y = 0 at (-3, 0, 2)
    {0.0, 0.0, 0.0},                       // unused: moving
};

glm::dmat3 rotation_y(double a) {
    const double c = std::cos(a), s = std::sin(a);
    // Columns (GLM is column-major): x axis, y axis, z axis images.
    return glm::dmat3(glm::dvec3(c, 0.0, -s), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(s, 0.0, c));
}

glm::dmat3 rotation_x(double a) {
    const double c = std::cos(a), s = std::sin(a);
    return glm::dmat3(glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, c, s), glm::dvec3(0.0, -s, c));
}

double intersect_sphere(double r, const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max) {
    // |o + t d|^2 = r^2, solved with the numerically stable form of the roots.
    const double a = glm::dot(d, d);
    const double hb = glm::dot(o, d);
    const double c = glm::dot(o, o) - r * r;
    const double disc = hb * hb - a * c;
    if (disc < 0.0) return -1.0;
    const double q = -(hb + std::copysign(std::sqrt(disc), hb));
    double t0 = q / a, t1 = (q != 0.0) ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 >= t_min && t0 < t_max) return t0;
    if (t1 >= t_min && t1 < t_max) return t1;  // near plane cut the front: the inside shows
    return -1.0;
}

double intersect_box(const glm::dvec3& h, const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max) {
    // Slab method.  A zero direction component gives +-inf bounds, handled by IEEE.
    double t_near = -INFINITY, t_far = INFINITY;
    for (int k = 0; k < 3; ++k) {
        if (d[k] == 0.0) {
            if (std::abs(o[k]) > h[k]) return -1.0;
            continue;
        }
        double a = (-h[k] - o[k]) / d[k], b = (h[k] - o[k]) / d[k];
        if (a > b) std::swap(a, b);
        t_near = std::max(t_near, a);
        t_far = std::min(t_far, b);
    }
    if (t_near > t_far) return -1.0;
    if (t_near >= t_min && t_near < t_max) return t_near;
    if (t_far >= t_min && t_far < t_max) return t_far;
    return -1.0;
}

double intersect_plane(const glm::dvec3& h, const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max) {
    if (d.y == 0.0) return -1.0;
    const double t = -o.y / d.y;
    if (!(t >= t_min && t < t_max)) return -1.0;
    const double x = o.x + t * d.x, z = o.z + t * d.z;
    return (std::abs(x) <= h.x && std::abs(z) <= h.z) ? t : -1.0;
}

}  // namespace

glm::dmat4 RigidTransform::matrix() const {
    glm::dmat4 m(rotation);
    m[3] = glm::dvec4(translation, 1.0);
    return m;
}

const ObjectShape& object_shape(int32_t id) { return kShapes[id]; }

RigidTransform object_transform(int32_t id, double t, double speed) {
    RigidTransform x;
    if (id != OBJECT_SPHERE_MOVING) {
        x.translation = kStaticPositions[id];
        return x;
    }
    // A Lissajous path in front of the boxes (x in [-1, 3], z in [2.2, 3.8],
    // y in [1.15, 1.35]: bottom >= 0.45 above the ground, >= 0.4 from the
    // floating box and the resting sphere),
    // about 0.1 units a frame at speed 1, plus a spin so object space rotates.
    const double s = t * speed;
    x.translation = glm::dvec3(1.0 + 2.0 * std::sin(0.05 * s), 1.25 + 0.1 * std::sin(0.11 * s), 3.0 + 0.8 * std::cos(0.037 * s));
    x.rotation = rotation_y(0.08 * s) * rotation_x(0.3 + 0.03 * s);
    return x;
}

double intersect_object(int32_t id, const glm::dvec3& origin, const glm::dvec3& dir, double t_min, double t_max) {
    return intersect_shape(kShapes[id], origin, dir, t_min, t_max);
}

double intersect_shape(const ObjectShape& s, const glm::dvec3& origin, const glm::dvec3& dir, double t_min, double t_max) {
    switch (s.shape) {
        case Shape::Plane: return intersect_plane(s.half, origin, dir, t_min, t_max);
        case Shape::Box: return intersect_box(s.half, origin, dir, t_min, t_max);
        case Shape::Sphere: return intersect_sphere(s.radius, origin, dir, t_min, t_max);
    }
    return -1.0;
}

double surface_distance(int32_t id, const glm::dvec3& p) { return shape_distance(kShapes[id], p); }

double shape_distance(const ObjectShape& s, const glm::dvec3& p) {
    switch (s.shape) {
        case Shape::Plane: {
            const double ex = std::max(std::abs(p.x) - s.half.x, 0.0);
            const double ez = std::max(std::abs(p.z) - s.half.z, 0.0);
            return std::sqrt(p.y * p.y + ex * ex + ez * ez);
        }
        case Shape::Box: {
            const glm::dvec3 q = glm::abs(p) - s.half;
            const double inside = std::max(q.x, std::max(q.y, q.z));
            if (inside <= 0.0) return -inside;
            return glm::length(glm::max(q, glm::dvec3(0.0)));
        }
        case Shape::Sphere: return std::abs(glm::length(p) - s.radius);
    }
    return INFINITY;
}

}  // namespace rrc_scene
