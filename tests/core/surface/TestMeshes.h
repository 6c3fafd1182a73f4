#pragma once
// Closed test meshes with known geometry for the method of spheres: boxes
// subdivided so that face centres, edge midpoints and corners are vertices, an
// icosphere with every vertex on the sphere, a torus with every vertex on the
// torus. All wound counter-clockwise seen from outside.

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "core/surface/TriangleMesh.h"

namespace lucent::test {

// The box lo .. lo + size with n[a] (even) cells along axis a.
inline TriangleMesh boxMesh(glm::dvec3 lo, glm::dvec3 size, glm::ivec3 n) {
    TriangleMesh mesh;
    std::map<std::array<int, 3>, std::uint32_t> index;
    auto vertex = [&](std::array<int, 3> g) {
        const auto [it, added] = index.try_emplace(g, std::uint32_t(mesh.vertices.size()));
        if (added) {
            mesh.vertices.push_back(lo + size * glm::dvec3(g[0], g[1], g[2]) / glm::dvec3(n));
        }
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3; // e_u × e_v = e_axis
        for (const int side : {0, 1}) {
            for (int i = 0; i < n[u]; ++i) {
                for (int j = 0; j < n[v]; ++j) {
                    std::array<std::uint32_t, 4> q;
                    const int corners[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
                    for (int c = 0; c < 4; ++c) {
                        std::array<int, 3> g{};
                        g[axis] = side * n[axis], g[u] = corners[c][0], g[v] = corners[c][1];
                        q[c] = vertex(g);
                    }
                    if (side == 0) {
                        std::swap(q[1], q[3]); // the low face looks the other way
                    }
                    mesh.triangles.push_back({q[0], q[1], q[2]});
                    mesh.triangles.push_back({q[0], q[2], q[3]});
                }
            }
        }
    }
    return mesh;
}

// Icosahedron of radius a subdivided `levels` times: 20·4^levels triangles.
inline TriangleMesh icosphere(double a, int levels) {
    const double p = (1.0 + std::sqrt(5.0)) / 2.0;
    TriangleMesh mesh;
    mesh.vertices = {{-1, p, 0},  {1, p, 0},  {-1, -p, 0}, {1, -p, 0}, {0, -1, p},  {0, 1, p},
                     {0, -1, -p}, {0, 1, -p}, {p, 0, -1},  {p, 0, 1},  {-p, 0, -1}, {-p, 0, 1}};
    mesh.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (glm::dvec3& v : mesh.vertices) {
        v = a * glm::normalize(v);
    }
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
        auto midpoint = [&](std::uint32_t i, std::uint32_t j) {
            const auto [it, added] = middle.try_emplace(std::minmax(i, j), 0u);
            if (added) {
                it->second = std::uint32_t(mesh.vertices.size());
                mesh.vertices.push_back(a * glm::normalize(mesh.vertices[i] + mesh.vertices[j]));
            }
            return it->second;
        };
        std::vector<glm::u32vec3> finer;
        for (const glm::u32vec3& t : mesh.triangles) {
            const std::uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z),
                                ca = midpoint(t.z, t.x);
            finer.insert(finer.end(), {{t.x, ab, ca}, {t.y, bc, ab}, {t.z, ca, bc}, {ab, bc, ca}});
        }
        mesh.triangles = std::move(finer);
    }
    return mesh;
}

// Torus about the z axis: major radius R0, minor r, nu × nv quads (nv even, so
// the inner equator v = π is a row of vertices). Vertex i·nv + j sits at
// u = 2πi/nu, v = 2πj/nv.
inline TriangleMesh torus(double R0, double r, int nu, int nv) {
    TriangleMesh mesh;
    for (int i = 0; i < nu; ++i) {
        const double u = 2.0 * std::numbers::pi * i / nu;
        for (int j = 0; j < nv; ++j) {
            const double v = 2.0 * std::numbers::pi * j / nv;
            const double rho = R0 + r * std::cos(v);
            mesh.vertices.push_back({rho * std::cos(u), rho * std::sin(u), r * std::sin(v)});
        }
    }
    auto at = [&](int i, int j) { return std::uint32_t((i % nu) * nv + (j % nv)); };
    for (int i = 0; i < nu; ++i) {
        for (int j = 0; j < nv; ++j) {
            mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    return mesh;
}

// The vertex nearest p.
inline std::uint32_t nearestVertex(const TriangleMesh& mesh, glm::dvec3 p) {
    std::uint32_t best = 0;
    double bestDistance = std::numeric_limits<double>::max();
    for (std::uint32_t i = 0; i < mesh.vertices.size(); ++i) {
        const double d = glm::length(mesh.vertices[i] - p);
        if (d < bestDistance) {
            best = i, bestDistance = d;
        }
    }
    return best;
}

inline long eulerCharacteristic(const TriangleMesh& mesh) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const glm::u32vec3& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
        }
    }
    return long(mesh.vertices.size()) - long(edges.size()) + long(mesh.triangles.size());
}

// The mesh moved by p → m·p + t.
inline TriangleMesh transformed(TriangleMesh mesh, const glm::dmat3& m, glm::dvec3 t) {
    for (glm::dvec3& v : mesh.vertices) {
        v = m * v + t;
    }
    return mesh;
}

} // namespace lucent::test
