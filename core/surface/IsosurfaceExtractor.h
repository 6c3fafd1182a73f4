#pragma once
// Isosurfaces of a volume as closed triangle meshes in patient coordinates
// (LPS mm), by flying-edges marching cubes (FlyingEdges.h) with the generated
// case table (MarchingCubesTable.h). The mesh is watertight, edge- and
// vertex-manifold and wound counter-clockwise seen from outside (normals point
// from high values to low values), whatever the voxel frame:
//  * vertices are keyed by the grid edge they lie on, never welded by position;
//  * voxels outside the volume or the clip box count as outside, so objects
//    cut by the field of view or the clip box are closed (their caps lie half
//    a voxel beyond the last voxel kept, at its face);
//  * crossings keep kMinEdgeFraction (1e-3) of an edge away from both voxels,
//    so voxels equal to the iso value never give zero-area triangles;
//  * the winding is flipped when the index-to-patient matrix mirrors
//    (negative determinant), so enclosed volumes stay positive.
// The vertex and triangle order does not depend on the number of threads.

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/surface/TriangleMesh.h"
#include "core/volume/BrickGrid.h"
#include "core/volume/Volume.h"

namespace lucent {

struct IsosurfaceOptions {
    // A voxel is inside when its value >= iso (HU for CT: volumes hold
    // rescaled values). Must lie within the volume's value range.
    double iso = 0.0;
    // Voxels whose index lies outside this box (inclusive, voxel index
    // coordinates) count as outside.
    ClipBox clip;
    // Gaussian pre-smoothing, standard deviation in voxels along each axis
    // (0: none). Meant for binary masks, whose raw surface over-estimates area
    // by about 9 %; sigma = 1 brings that under 1 %. Costs two float copies of
    // the clip box.
    double smoothingSigma = 0.0;
    // Called on the calling thread, between chunks of work, with the fraction
    // done (0 .. 1). Returning false stops the work: extractIsosurface then
    // throws IsosurfaceCancelled. An exception thrown by the hook propagates.
    std::function<bool(double fractionDone)> progress;
};

struct IsosurfaceResult {
    TriangleMesh mesh;
    double extractMs = 0.0; // wall time of the whole call, smoothing included
    double smoothMs = 0.0;  // of which the Gaussian pre-smoothing
    int threads = 0;        // OpenMP threads available to the call
    // The voxel range contoured (the clip box within the volume), inclusive.
    glm::ivec3 first{0};
    glm::ivec3 last{-1};
    // What the caller should tell the user: a binary input contoured without
    // smoothing, a clip box that holds no voxel.
    std::vector<std::string> warnings;
};

// Thrown when the progress hook asked to stop; no partial mesh is returned.
class IsosurfaceCancelled : public std::runtime_error {
public:
    IsosurfaceCancelled() : std::runtime_error("isosurface extraction cancelled") {}
};

// Throws std::invalid_argument for an empty volume, a non-finite iso value or
// one outside the volume's value range (the message names both), or a
// negative or non-finite sigma; std::length_error when the mesh would need
// 2^32 vertices or more.
IsosurfaceResult extractIsosurface(const Volume& volume, const IsosurfaceOptions& options);

} // namespace lucent
