#include "core/surface/MeshTopology.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace lucent {

std::vector<HalfEdge> sortedHalfEdges(const TriangleMesh& mesh) {
    const std::size_t vertexCount = mesh.vertices.size();
    if (vertexCount >= (std::size_t(1) << 31)) {
        throw std::length_error("mesh topology: 2^31 vertices or more");
    }
    std::vector<HalfEdge> halfEdges;
    halfEdges.reserve(3 * mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::u32vec3& tri = mesh.triangles[t];
        for (int c = 0; c < 3; ++c) {
            if (tri[c] >= vertexCount) {
                throw std::invalid_argument("mesh topology: triangle " + std::to_string(t) +
                                            " uses vertex " + std::to_string(tri[c]) + " of " +
                                            std::to_string(vertexCount));
            }
        }
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
            continue;
        }
        for (int c = 0; c < 3; ++c) {
            const std::uint64_t a = tri[c];
            const std::uint64_t b = tri[(c + 1) % 3];
            const std::uint64_t key = a < b ? (a << 33 | b << 1) : (b << 33 | a << 1 | 1u);
            halfEdges.push_back({key, static_cast<std::uint32_t>(3 * t + c)});
        }
    }
    std::sort(halfEdges.begin(), halfEdges.end(), [](const HalfEdge& x, const HalfEdge& y) {
        return x.key != y.key ? x.key < y.key : x.index < y.index;
    });
    return halfEdges;
}

DisjointSets::DisjointSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), std::uint32_t(0));
}

std::uint32_t DisjointSets::find(std::uint32_t x) {
    while (parent_[x] != x) {
        parent_[x] = parent_[parent_[x]];
        x = parent_[x];
    }
    return x;
}

void DisjointSets::unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a < b) {
        parent_[b] = a;
    } else if (b < a) {
        parent_[a] = b;
    }
}

TriangleComponents triangleComponents(const TriangleMesh& mesh) {
    DisjointSets sets(mesh.vertices.size());
    for (const glm::u32vec3& t : mesh.triangles) {
        sets.unite(t[0], t[1]);
        sets.unite(t[0], t[2]);
    }
    TriangleComponents out;
    out.label.resize(mesh.triangles.size());
    constexpr std::uint32_t kNone = ~std::uint32_t(0);
    std::vector<std::uint32_t> labelOfRoot(mesh.vertices.size(), kNone);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        std::uint32_t& label = labelOfRoot[sets.find(mesh.triangles[t][0])];
        if (label == kNone) {
            label = static_cast<std::uint32_t>(out.count++);
        }
        out.label[t] = label;
    }
    return out;
}

std::size_t removeUnusedVertices(TriangleMesh& mesh) {
    constexpr std::uint32_t kUnused = ~std::uint32_t(0);
    std::vector<std::uint32_t> newIndex(mesh.vertices.size(), kUnused);
    for (const glm::u32vec3& t : mesh.triangles) {
        for (int c = 0; c < 3; ++c) {
            newIndex[t[c]] = 0;
        }
    }
    std::uint32_t kept = 0;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        if (newIndex[v] != kUnused) {
            mesh.vertices[kept] = mesh.vertices[v];
            newIndex[v] = kept++;
        }
    }
    const std::size_t removed = mesh.vertices.size() - kept;
    mesh.vertices.resize(kept);
    for (glm::u32vec3& t : mesh.triangles) {
        t = {newIndex[t[0]], newIndex[t[1]], newIndex[t[2]]};
    }
    return removed;
}

} // namespace lucent
