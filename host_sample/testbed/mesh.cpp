#include "mesh.h"

#include <cmath>

namespace rrc_sample {
namespace {

const float kPi = 3.14159265358979f;

void quad(MeshData& m, glm::vec3 o, glm::vec3 a, glm::vec3 b, glm::vec3 n) {
    // o, o+a, o+a+b, o+b: counter-clockwise around n when a x b points along n.
    const uint32_t base = (uint32_t)m.vertices.size();
    m.vertices.push_back({o, n});
    m.vertices.push_back({o + a, n});
    m.vertices.push_back({o + a + b, n});
    m.vertices.push_back({o + b, n});
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
}

// Two triangles per cell of a (rows + 1) x (columns + 1) vertex grid laid
// out row by row (spheres: stacks x slices; tori: segments x sides).
void add_grid_indices(MeshData& m, int rows, int columns) {
    const uint32_t row = (uint32_t)columns + 1;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            const uint32_t a = (uint32_t)j * row + (uint32_t)i, b = a + row;
            for (uint32_t k : {a, b, b + 1, a, b + 1, a + 1}) m.indices.push_back(k);
        }
}

}  // namespace

MeshData make_plane(float half, int n) {
    MeshData m;
    const float step = 2.0f * half / (float)n;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) quad(m, {-half + i * step, 0.0f, -half + j * step}, {0, 0, step}, {step, 0, 0}, {0, 1, 0});
    return m;
}

MeshData make_box(glm::vec3 h) {
    MeshData m;
    quad(m, {-h.x, -h.y, h.z}, {2 * h.x, 0, 0}, {0, 2 * h.y, 0}, {0, 0, 1});    // +z
    quad(m, {h.x, -h.y, -h.z}, {-2 * h.x, 0, 0}, {0, 2 * h.y, 0}, {0, 0, -1});  // -z
    quad(m, {h.x, -h.y, h.z}, {0, 0, -2 * h.z}, {0, 2 * h.y, 0}, {1, 0, 0});    // +x
    quad(m, {-h.x, -h.y, -h.z}, {0, 0, 2 * h.z}, {0, 2 * h.y, 0}, {-1, 0, 0});  // -x
    quad(m, {-h.x, h.y, h.z}, {2 * h.x, 0, 0}, {0, 0, -2 * h.z}, {0, 1, 0});    // +y
    quad(m, {-h.x, -h.y, -h.z}, {2 * h.x, 0, 0}, {0, 0, 2 * h.z}, {0, -1, 0});  // -y
    return m;
}

MeshData make_cylinder(float radius, float height, int segments) {
    MeshData m;
    for (int i = 0; i <= segments; ++i) {
        const float a = 2.0f * kPi * (float)i / (float)segments;
        const glm::vec3 n(std::cos(a), 0.0f, -std::sin(a));
        m.vertices.push_back({n * radius, n});
        m.vertices.push_back({n * radius + glm::vec3(0, height, 0), n});
    }
    for (int i = 0; i < segments; ++i) {
        const uint32_t b = 2u * (uint32_t)i;
        for (uint32_t k : {b, b + 2, b + 3, b, b + 3, b + 1}) m.indices.push_back(k);
    }
    for (int cap = 0; cap < 2; ++cap) {
        const float y = cap ? height : 0.0f;
        const glm::vec3 n(0, cap ? 1.0f : -1.0f, 0);
        const uint32_t centre = (uint32_t)m.vertices.size();
        m.vertices.push_back({{0, y, 0}, n});
        for (int i = 0; i <= segments; ++i) {
            const float a = 2.0f * kPi * (float)i / (float)segments;
            m.vertices.push_back({{radius * std::cos(a), y, -radius * std::sin(a)}, n});
        }
        for (int i = 0; i < segments; ++i) {
            const uint32_t a = centre + 1 + (uint32_t)i, b = a + 1;
            if (cap) {
                for (uint32_t k : {centre, a, b}) m.indices.push_back(k);
            } else {
                for (uint32_t k : {centre, b, a}) m.indices.push_back(k);
            }
        }
    }
    return m;
}

MeshData make_sphere(float radius, int slices, int stacks) {
    MeshData m;
    for (int j = 0; j <= stacks; ++j) {
        const float phi = kPi * (float)j / (float)stacks;  // from +y down
        for (int i = 0; i <= slices; ++i) {
            const float theta = 2.0f * kPi * (float)i / (float)slices;
            const glm::vec3 n(std::sin(phi) * std::cos(theta), std::cos(phi), -std::sin(phi) * std::sin(theta));
            m.vertices.push_back({n * radius, n});
        }
    }
    add_grid_indices(m, stacks, slices);
    return m;
}

MeshData make_torus(float R, float r, int segments, int sides) {
    MeshData m;
    for (int j = 0; j <= segments; ++j) {
        const float u = 2.0f * kPi * (float)j / (float)segments;
        const glm::vec3 dir(std::cos(u), 0.0f, -std::sin(u));
        for (int i = 0; i <= sides; ++i) {
            const float v = 2.0f * kPi * (float)i / (float)sides;
            const glm::vec3 n = dir * std::cos(v) + glm::vec3(0, std::sin(v), 0);
            m.vertices.push_back({dir * R + n * r, n});
        }
    }
    add_grid_indices(m, segments, sides);
    return m;
}

}  // namespace rrc_sample
