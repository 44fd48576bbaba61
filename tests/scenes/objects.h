// The fixed set of objects of the analytic test scene and their motion.
//
// World space is right-handed, y up, the ground is the plane y = 0.  Every
// object is described in its own object space and placed by a rigid model
// transform (rotation + translation, no scale), so a ray keeps its parameter t
// when it is moved into object space and distances are the same in both.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace rrc_scene {

// Object ids as written to Frame::object_id.  -1 is the sky (nothing hit).
enum ObjectId : int32_t {
    OBJECT_BACKGROUND = -1,
    OBJECT_GROUND = 0,          // square 60 x 60 on y = 0 (finite: its far edge shows the sky)
    OBJECT_BOX_LARGE = 1,       // cube resting on the ground
    OBJECT_BOX_LONG = 2,        // long box resting on the ground
    OBJECT_BOX_FLOATING = 3,    // flat box in the air: clean disocclusions, no contact
    OBJECT_SPHERE_RESTING = 4,  // sphere touching the ground in one point (a contact)
    OBJECT_SPHERE_MOVING = 5,   // floating sphere that translates and spins: object motion
    OBJECT_COUNT = 6,           // the objects of the default layout (SceneLayout::OBJECTS): ids 0 .. 5
    // The thin-card layout (SceneLayout::THIN_CARD, scene.h): its own two
    // objects, whose size and placement depend on the scene's configuration.
    OBJECT_WALL = 6,     // a large plane seen at a chosen angle from its normal
    OBJECT_CARD = 7,     // a thin card just in front of the wall, sliding along it
    OBJECT_ID_COUNT = 8  // every id of every layout: sizes per-id tables
};

enum class Shape { Plane, Box, Sphere };

// Geometry in object space: a plane is y = 0 with |x|, |z| <= half.x, half.z;
// a box is centred at the origin with half extents `half`; a sphere is centred
// at the origin with radius `radius`.
struct ObjectShape {
    Shape shape;
    glm::dvec3 half;
    double radius;
};

// Rigid transform p_world = rotation * p_object + translation.
struct RigidTransform {
    glm::dmat3 rotation{1.0};
    glm::dvec3 translation{0.0};

    glm::dvec3 to_world(const glm::dvec3& p) const { return rotation * p + translation; }
    glm::dvec3 dir_to_world(const glm::dvec3& d) const { return rotation * d; }
    // The inverse of a rotation is its transpose: exact enough and cheap.
    glm::dvec3 to_object(const glm::dvec3& p) const { return glm::transpose(rotation) * (p - translation); }
    glm::dvec3 dir_to_object(const glm::dvec3& d) const { return glm::transpose(rotation) * d; }
    glm::dmat4 matrix() const;  // column-major 4x4 model matrix
};

// The default layout's objects (ids below OBJECT_COUNT).
const ObjectShape& object_shape(int32_t id);

// Model transform of object `id` at time `t` (in frames).  Only
// OBJECT_SPHERE_MOVING depends on t; `speed` scales its motion.
RigidTransform object_transform(int32_t id, double t, double speed);

// Smallest ray parameter t in [t_min, t_max) where the object-space ray
// origin + t * dir meets the object's surface, or -1 if none.
double intersect_object(int32_t id, const glm::dvec3& origin, const glm::dvec3& dir, double t_min, double t_max);

// Unsigned Euclidean distance from an object-space point to the object's surface.
double surface_distance(int32_t id, const glm::dvec3& p);

// The same two for any shape (the thin-card layout's objects are sized at run time).
double intersect_shape(const ObjectShape& shape, const glm::dvec3& origin, const glm::dvec3& dir, double t_min, double t_max);
double shape_distance(const ObjectShape& shape, const glm::dvec3& p);

}  // namespace rrc_scene
