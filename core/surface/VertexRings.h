#pragma once
// The triangles around each vertex (vertex → triangle CSR) and what the method
// of spheres needs from them: the interior solid angle Ω_int of the solid's
// tangent cone at a vertex, from the dihedral angles of its one-ring.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/surface/TriangleMesh.h"

namespace lucent {

class VertexRings {
public:
    // Keeps a reference to `mesh`. Throws std::invalid_argument when a triangle
    // names a vertex that does not exist.
    explicit VertexRings(const TriangleMesh& mesh);

    std::span<const std::uint32_t> trianglesAt(std::uint32_t vertex) const {
        return {entries_.data() + start_[vertex], entries_.data() + start_[vertex + 1]};
    }

    std::size_t memoryBytes() const {
        return (start_.size() + entries_.size()) * sizeof(std::uint32_t);
    }

    // Ω_int = Σ β_i − (k − 2m)·π over the k ring edges (interior dihedral angle
    // β_i each) of the m closed fans at the vertex: Gauss–Bonnet on the link
    // polygon. 2π on a flat face, π on a 90° edge, π/2 at a cube corner.
    // nullopt when the fan is not closed (a boundary or non-manifold edge, a
    // repeated directed edge) or no triangle uses the vertex. `scratch` is
    // reused between calls to keep them allocation-free.
    std::optional<double> interiorSolidAngle(std::uint32_t vertex,
                                             std::vector<std::uint32_t>& scratch) const;

private:
    const TriangleMesh& mesh_;
    std::vector<std::uint32_t> start_;   // CSR offsets, one per vertex + 1
    std::vector<std::uint32_t> entries_; // triangle ids
};

} // namespace lucent
