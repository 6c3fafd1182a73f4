#include "core/surface/VertexNormals.h"

namespace lucent {

std::vector<glm::dvec3> triangleNormals(const TriangleMesh& mesh) {
    std::vector<glm::dvec3> normals(mesh.triangles.size());
    const std::ptrdiff_t n = std::ptrdiff_t(mesh.triangles.size());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t t = 0; t < n; ++t) {
        const glm::u32vec3 tri = mesh.triangles[std::size_t(t)];
        const glm::dvec3 c = glm::cross(mesh.vertices[tri.y] - mesh.vertices[tri.x],
                                        mesh.vertices[tri.z] - mesh.vertices[tri.x]);
        const double length = glm::length(c);
        normals[std::size_t(t)] = length > 0.0 ? c / length : glm::dvec3(0.0);
    }
    return normals;
}

std::vector<glm::dvec3> vertexNormals(const TriangleMesh& mesh) {
    // The unnormalised cross product is the normal times twice the area.
    std::vector<glm::dvec3> sums(mesh.vertices.size(), glm::dvec3(0.0));
    for (const glm::u32vec3& tri : mesh.triangles) {
        const glm::dvec3 c = glm::cross(mesh.vertices[tri.y] - mesh.vertices[tri.x],
                                        mesh.vertices[tri.z] - mesh.vertices[tri.x]);
        sums[tri.x] += c;
        sums[tri.y] += c;
        sums[tri.z] += c;
    }
    for (glm::dvec3& s : sums) {
        const double length = glm::length(s);
        s = length > 0.0 ? s / length : glm::dvec3(0.0);
    }
    return sums;
}

} // namespace lucent
