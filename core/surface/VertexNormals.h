#pragma once
// Unit normals of a mesh: per triangle (right-hand rule: outward for a mesh
// wound as TriangleMesh says) and per vertex (the area-weighted mean of its
// triangles' normals), for lighting and for the mesh files.

#include <vector>

#include "core/surface/TriangleMesh.h"

namespace lucent {

// Zero for a triangle without area.
std::vector<glm::dvec3> triangleNormals(const TriangleMesh& mesh);
// Zero for a vertex of no triangle (or of zero-area ones only).
std::vector<glm::dvec3> vertexNormals(const TriangleMesh& mesh);

} // namespace lucent
