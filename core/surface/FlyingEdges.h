#pragma once
// Internal to the isosurface extractor: marching cubes over a voxel block in
// the flying-edges order (Schroeder, Maynard, Geveci 2015):
//  1. classify the x-edges of every row (inside = value >= iso) and note where
//     the first and last crossing lie;
//  2. per row of cells, count triangles and y/z crossings inside that range;
//  3. prefix sums give each row its place in the output;
//  4. per row of cells, write vertices and triangles into the preallocated mesh.
// Passes 1, 2 and 4 run in parallel over z-slabs; each row owns fixed output
// ranges, so the mesh is the same for any thread count. Vertices are keyed by
// the grid edge they lie on and written once (never welded by position).
//
// The block is surrounded by a virtual layer of outside voxels (no copy), so
// every surface is closed. A vertex between a block voxel and that layer sits
// half-way (t = 0.5), at the face of the voxel.

#include <functional>

#include <glm/glm.hpp>

#include "core/surface/TriangleMesh.h"
#include "core/surface/VoxelBlock.h"

namespace lucent {

// Edge crossings are kept at least this far (as a fraction of the edge) from
// either voxel: voxels equal to the iso value would otherwise put vertices of
// several edges on one grid point (zero-area triangles), and points closer
// than about 1e-4 voxel merge once written as float32 (STL, PLY).
inline constexpr double kMinEdgeFraction = 1e-3;

struct ContourSettings {
    double iso = 0.0;
    glm::dmat4 blockToPatient{1.0}; // block index (i, j, k) -> LPS mm
    bool flipWinding = false;       // for a mirrored (negative determinant) frame
    std::function<bool(double)> progress;
    double progressFrom = 0.0; // the share of the progress range this call fills
    double progressTo = 1.0;
};

// Contours the block into out (replacing its contents). Returns false when the
// progress hook asked to stop (out is then empty). Throws std::length_error
// when the mesh would need 2^32 vertices or more.
template <class T>
bool contourBlock(const VoxelBlock<T>& block, const ContourSettings& settings, TriangleMesh& out);

} // namespace lucent
