#include "core/surface/VertexRings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace lucent {

namespace {

glm::dvec3 unitNormal(const TriangleMesh& mesh, const glm::u32vec3& t) {
    const glm::dvec3 cross = glm::cross(mesh.vertices[t.y] - mesh.vertices[t.x],
                                        mesh.vertices[t.z] - mesh.vertices[t.x]);
    const double length = glm::length(cross);
    return length > 0.0 ? cross / length : glm::dvec3(0.0);
}

// Interior dihedral angle β ∈ (0, 2π) of the solid at the edge x → a, between
// the triangle `in` (which holds a → x) and `out` (which holds x → a):
// π on a flat surface, less at a convex edge.
double interiorDihedral(const TriangleMesh& mesh, std::uint32_t in, std::uint32_t out,
                        std::uint32_t x, std::uint32_t a) {
    const glm::dvec3 nIn = unitNormal(mesh, mesh.triangles[in]);
    const glm::dvec3 nOut = unitNormal(mesh, mesh.triangles[out]);
    const glm::dvec3 edge = mesh.vertices[a] - mesh.vertices[x];
    const double length = glm::length(edge);
    const glm::dvec3 e = length > 0.0 ? edge / length : glm::dvec3(0.0);
    return std::numbers::pi + std::atan2(glm::dot(glm::cross(nIn, nOut), e), glm::dot(nIn, nOut));
}

// follower[i] = the j with prev[j] == next[i]; false unless that j is unique
// and no two triangles share a "next" (a closed, consistently wound fan).
bool findFollowers(std::span<const std::uint32_t> next, std::span<const std::uint32_t> prev,
                   std::span<std::uint32_t> follower) {
    for (std::size_t i = 0; i < next.size(); ++i) {
        std::size_t matches = 0, sameNext = 0;
        for (std::size_t j = 0; j < next.size(); ++j) {
            if (prev[j] == next[i]) {
                follower[i] = std::uint32_t(j), ++matches;
            }
            sameNext += next[j] == next[i] ? 1 : 0;
        }
        if (matches != 1 || sameNext != 1) {
            return false;
        }
    }
    return true;
}

// Number of cycles of the permutation `follower` (the fans around the vertex).
std::size_t countCycles(std::span<const std::uint32_t> follower, std::span<std::uint32_t> seen) {
    std::fill(seen.begin(), seen.end(), 0u);
    std::size_t cycles = 0;
    for (std::size_t i = 0; i < follower.size(); ++i) {
        if (seen[i] == 0) {
            ++cycles;
            for (std::size_t j = i; seen[j] == 0; j = follower[j]) {
                seen[j] = 1;
            }
        }
    }
    return cycles;
}

} // namespace

VertexRings::VertexRings(const TriangleMesh& mesh)
    : mesh_(mesh), start_(mesh.vertices.size() + 1, 0u) {
    const std::size_t n = mesh.vertices.size();
    if (n >= std::numeric_limits<std::uint32_t>::max() ||
        3 * mesh.triangles.size() >= std::numeric_limits<std::uint32_t>::max()) {
        throw std::invalid_argument("mesh too large for 32-bit vertex rings");
    }
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::u32vec3& t = mesh.triangles[i];
        if (t.x >= n || t.y >= n || t.z >= n) {
            throw std::invalid_argument("triangle " + std::to_string(i) +
                                        " names a vertex beyond the " + std::to_string(n) +
                                        " vertices");
        }
        ++start_[t.x + 1], ++start_[t.y + 1], ++start_[t.z + 1];
    }
    for (std::size_t v = 1; v <= n; ++v) {
        start_[v] += start_[v - 1];
    }
    entries_.resize(start_[n]);
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::u32vec3& t = mesh.triangles[i];
        entries_[fill[t.x]++] = i, entries_[fill[t.y]++] = i, entries_[fill[t.z]++] = i;
    }
}

std::optional<double> VertexRings::interiorSolidAngle(std::uint32_t vertex,
                                                      std::vector<std::uint32_t>& scratch) const {
    const std::span<const std::uint32_t> ring = trianglesAt(vertex);
    const std::size_t k = ring.size();
    if (k < 3) {
        return std::nullopt;
    }
    // Per ring triangle i: the vertex after and before `vertex` (CCW), and the
    // ring triangle that follows i around the vertex (its "before" is i's "after").
    scratch.resize(4 * k);
    const std::span<std::uint32_t> next(scratch.data(), k), prev(scratch.data() + k, k),
        follower(scratch.data() + 2 * k, k), seen(scratch.data() + 3 * k, k);
    for (std::size_t i = 0; i < k; ++i) {
        const glm::u32vec3& t = mesh_.triangles[ring[i]];
        const int j = t.x == vertex ? 0 : (t.y == vertex ? 1 : 2);
        next[i] = t[(j + 1) % 3], prev[i] = t[(j + 2) % 3];
        if (next[i] == vertex || prev[i] == vertex) {
            return std::nullopt; // a triangle that names the vertex twice
        }
    }
    if (!findFollowers(next, prev, follower)) {
        return std::nullopt;
    }
    double betaSum = 0.0;
    for (std::size_t i = 0; i < k; ++i) {
        betaSum += interiorDihedral(mesh_, ring[follower[i]], ring[i], vertex, next[i]);
    }
    const std::size_t fans = countCycles(follower, seen);
    return betaSum - (double(k) - 2.0 * double(fans)) * std::numbers::pi;
}

} // namespace lucent
