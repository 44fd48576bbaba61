// Generated meshes (no files to ship): positions and normals, indexed
// triangles, counter-clockwise seen from outside in a right-handed frame.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rrc_sample {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
};

struct MeshData {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
};

/** A square in the y = 0 plane, normal +y, side 2*half, split into n x n quads. */
MeshData make_plane(float half, int n);
/** An axis-aligned box centred at the origin with the given half extents. */
MeshData make_box(glm::vec3 half);
/** A capped cylinder along +y from y = 0 to y = height. */
MeshData make_cylinder(float radius, float height, int segments);
/** A UV sphere centred at the origin. */
MeshData make_sphere(float radius, int slices, int stacks);
/** A torus around the y axis: ring radius R, tube radius r. */
MeshData make_torus(float R, float r, int segments, int sides);

}  // namespace rrc_sample
