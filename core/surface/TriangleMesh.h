#pragma once
// A triangle mesh in patient coordinates (LPS, millimetres): shared vertices
// and triangles of three vertex indices, wound counter-clockwise seen from
// outside the solid (right-hand normals point out of it). What the isosurface
// extractor makes, the clean-up changes, the method of spheres measures and
// the mesh files hold.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

struct TriangleMesh {
    std::vector<glm::dvec3> vertices;
    std::vector<glm::u32vec3> triangles;

    bool empty() const { return triangles.empty(); }
};

} // namespace lucent
