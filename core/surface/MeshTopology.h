#pragma once
// Edge and connectivity structure of a triangle mesh, shared by the mesh checks
// and the clean-up: half-edges sorted by their undirected edge (no map per
// edge), and disjoint sets for components and fans.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/surface/TriangleMesh.h"

namespace lucent {

// The half-edge of triangle t from corner c to corner (c + 1) % 3.
struct HalfEdge {
    // The undirected edge {lo, hi} and the direction: lo << 33 | hi << 1 |
    // (1 when the half-edge runs from hi to lo). Equal keys are equal directed edges.
    std::uint64_t key = 0;
    std::uint32_t index = 0; // 3 * t + c

    std::uint32_t triangle() const { return index / 3; }
    std::uint32_t corner() const { return index % 3; }
    std::uint64_t edge() const { return key >> 1; }
    std::uint32_t low() const { return static_cast<std::uint32_t>(key >> 33); }
    std::uint32_t high() const { return static_cast<std::uint32_t>((key >> 1) & 0xffffffffu); }
};

// Every half-edge of the triangles that have three distinct vertices, sorted
// by key, then index: the half-edges of one undirected edge are adjacent.
// Throws std::invalid_argument for a vertex index out of range and
// std::length_error for 2^31 vertices or more.
std::vector<HalfEdge> sortedHalfEdges(const TriangleMesh& mesh);

// Union-find over 0..n-1 with path halving; the smaller index becomes the root,
// so the result does not depend on the order of unions.
class DisjointSets {
public:
    explicit DisjointSets(std::size_t n);
    std::uint32_t find(std::uint32_t x);
    void unite(std::uint32_t a, std::uint32_t b);

private:
    std::vector<std::uint32_t> parent_;
};

// Connected components of the triangles, joined by shared vertices. Labels are
// 0, 1, ... in the order of each component's first triangle.
struct TriangleComponents {
    std::vector<std::uint32_t> label; // per triangle
    std::size_t count = 0;
};
TriangleComponents triangleComponents(const TriangleMesh& mesh);

// Keeps the vertices that some triangle uses, in their order, and renumbers the
// triangles. Returns how many vertices were removed.
std::size_t removeUnusedVertices(TriangleMesh& mesh);

} // namespace lucent
