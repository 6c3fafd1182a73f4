#pragma once
// What a triangle mesh is: its size and geometry (area, enclosed volume,
// longest edge) and whether it is a closed, manifold, consistently oriented
// surface that a slicer, a renderer or the method of spheres can trust.

#include <cstddef>

#include "core/surface/TriangleMesh.h"

namespace lucent {

struct MeshReport {
    std::size_t triangles = 0;
    std::size_t vertices = 0;       // used by at least one triangle
    std::size_t unusedVertices = 0; // used by none
    std::size_t edges = 0;          // undirected, of triangles with three distinct vertices

    double area = 0.0;   // mm²
    double volume = 0.0; // signed enclosed volume, mm³: > 0 when normals point out
    double hMax = 0.0;   // longest edge, mm

    std::size_t boundaryEdges = 0;         // edges of one triangle
    std::size_t nonManifoldEdges = 0;      // edges of three or more triangles
    std::size_t nonManifoldVertices = 0;   // vertices whose triangles form more than one fan
    std::size_t repeatedDirectedEdges = 0; // a directed edge used again (flipped neighbour)
    // A repeated vertex index, or |cross product| <= 1e-12 * (longest side)²:
    // no normal can be computed from it.
    std::size_t zeroAreaTriangles = 0;

    std::size_t components = 0; // connected by shared vertices
    long long euler = 0;        // vertices - edges + triangles (2 per closed sphere-like part)

    bool watertight() const { return boundaryEdges == 0 && nonManifoldEdges == 0; }
    // Watertight, vertex-manifold and consistently oriented.
    bool closedManifold() const {
        return watertight() && nonManifoldVertices == 0 && repeatedDirectedEdges == 0;
    }
};

// Everything above in O(n log n) (one sort of the half-edges). Throws
// std::invalid_argument when a triangle uses a vertex that does not exist.
MeshReport checkMesh(const TriangleMesh& mesh);

// The total area (mm²) and the signed enclosed volume (mm³) alone, in O(n).
double meshArea(const TriangleMesh& mesh);
double meshVolume(const TriangleMesh& mesh);

} // namespace lucent
