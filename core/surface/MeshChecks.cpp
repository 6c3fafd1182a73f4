#include "core/surface/MeshChecks.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/surface/MeshTopology.h"

namespace lucent {

namespace {

// Volumes are summed about the centre of the bounding box: far from the
// patient origin the terms would otherwise cancel badly.
glm::dvec3 boxCentre(const TriangleMesh& mesh) {
    if (mesh.vertices.empty()) {
        return glm::dvec3(0.0);
    }
    glm::dvec3 lo = mesh.vertices.front(), hi = lo;
    for (const glm::dvec3& v : mesh.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    return 0.5 * (lo + hi);
}

void addGeometry(const TriangleMesh& mesh, MeshReport& r) {
    const glm::dvec3 centre = boxCentre(mesh);
    for (const glm::u32vec3& t : mesh.triangles) {
        const glm::dvec3 a = mesh.vertices[t[0]] - centre;
        const glm::dvec3 b = mesh.vertices[t[1]] - centre;
        const glm::dvec3 c = mesh.vertices[t[2]] - centre;
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double twiceArea = glm::length(n);
        const double longest2 =
            std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
        r.area += 0.5 * twiceArea;
        r.volume += glm::dot(a, glm::cross(b, c)) / 6.0;
        r.hMax = std::max(r.hMax, longest2);
        const bool repeated = t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
        if (repeated || twiceArea <= 1e-12 * longest2) {
            ++r.zeroAreaTriangles;
        }
    }
    r.hMax = std::sqrt(r.hMax);
}

// The corner of half-edge h's triangle that sits on vertex v.
std::uint32_t cornerAt(const TriangleMesh& mesh, const HalfEdge& h, std::uint32_t v) {
    const std::uint32_t t = h.triangle();
    const std::uint32_t c = h.corner();
    return mesh.triangles[t][c] == v ? 3 * t + c : 3 * t + (c + 1) % 3;
}

// Counts edges by how many triangles share them, and joins the corners of
// triangles that share an edge into fans around each vertex.
void addEdges(const TriangleMesh& mesh, MeshReport& r, DisjointSets& fans) {
    const std::vector<HalfEdge> halfEdges = sortedHalfEdges(mesh);
    std::size_t begin = 0;
    while (begin < halfEdges.size()) {
        std::size_t end = begin + 1;
        while (end < halfEdges.size() && halfEdges[end].edge() == halfEdges[begin].edge()) {
            if (halfEdges[end].key == halfEdges[end - 1].key) {
                ++r.repeatedDirectedEdges;
            }
            for (const std::uint32_t v : {halfEdges[begin].low(), halfEdges[begin].high()}) {
                fans.unite(cornerAt(mesh, halfEdges[end - 1], v),
                           cornerAt(mesh, halfEdges[end], v));
            }
            ++end;
        }
        const std::size_t uses = end - begin;
        ++r.edges;
        r.boundaryEdges += uses == 1 ? 1 : 0;
        r.nonManifoldEdges += uses > 2 ? 1 : 0;
        begin = end;
    }
}

void addVertices(const TriangleMesh& mesh, MeshReport& r, DisjointSets& fans) {
    std::vector<std::uint32_t> fanCount(mesh.vertices.size(), 0);
    for (std::uint32_t corner = 0; corner < 3 * mesh.triangles.size(); ++corner) {
        if (fans.find(corner) == corner) {
            ++fanCount[mesh.triangles[corner / 3][corner % 3]];
        }
    }
    for (const std::uint32_t n : fanCount) {
        r.vertices += n > 0 ? 1 : 0;
        r.nonManifoldVertices += n > 1 ? 1 : 0;
    }
    r.unusedVertices = mesh.vertices.size() - r.vertices;
}

} // namespace

MeshReport checkMesh(const TriangleMesh& mesh) {
    MeshReport r;
    r.triangles = mesh.triangles.size();
    DisjointSets fans(3 * mesh.triangles.size());
    addEdges(mesh, r, fans); // validates the indices first
    addGeometry(mesh, r);
    addVertices(mesh, r, fans);
    r.components = triangleComponents(mesh).count;
    r.euler = static_cast<long long>(r.vertices) - static_cast<long long>(r.edges) +
              static_cast<long long>(r.triangles);
    return r;
}

double meshArea(const TriangleMesh& mesh) {
    double area = 0.0;
    for (const glm::u32vec3& t : mesh.triangles) {
        const glm::dvec3& a = mesh.vertices[t[0]];
        area += 0.5 * glm::length(glm::cross(mesh.vertices[t[1]] - a, mesh.vertices[t[2]] - a));
    }
    return area;
}

double meshVolume(const TriangleMesh& mesh) {
    const glm::dvec3 centre = boxCentre(mesh);
    double volume = 0.0;
    for (const glm::u32vec3& t : mesh.triangles) {
        volume += glm::dot(mesh.vertices[t[0]] - centre,
                           glm::cross(mesh.vertices[t[1]] - centre, mesh.vertices[t[2]] - centre));
    }
    return volume / 6.0;
}

} // namespace lucent
