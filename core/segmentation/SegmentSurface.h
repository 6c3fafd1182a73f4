#pragma once
// A segment's surface, through the surfaces module (core/surface/SurfacePipeline.h): the mask
// on the smallest box of its grid that holds it (and the smoothing's reach), a Gaussian
// pre-smoothing of the binary mask, flying edges at half-way, and optional windowed-sinc
// smoothing and decimation; in patient LPS mm, for the 3D view (core/scene/SurfaceDisplay.h)
// and the mesh files (core/formats/MeshFiles.h: STL, PLY, OBJ for printing).

#include "core/segmentation/SegmentMask.h"
#include "core/surface/SurfacePipeline.h"
#include "core/volume/Volume.h"

namespace lucent {

struct SegmentSurfaceOptions {
    // Gaussian pre-smoothing of the mask, voxels: 1 takes the binary mask's staircase away
    // (its raw surface over-estimates the area by about 9 %), as lucent-cli surface does for
    // masks; 0: the voxel faces' staircase as it is.
    double sigma = 1.0;
    int smoothIterations = 0; // windowed-sinc iterations after extraction (0: none)
    double decimate = 0.0;    // the fraction of triangles to remove, [0, 1)
};

// std::invalid_argument for a mask on another grid, std::runtime_error naming the segment's
// name for an empty one (nothing to show or print).
SurfaceResult segmentSurface(const SegmentMask& mask, const VolumeGeometry& grid,
                             const SegmentSurfaceOptions& options = {},
                             const std::string& name = "segment");

} // namespace lucent
