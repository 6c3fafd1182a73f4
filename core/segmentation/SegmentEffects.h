#pragma once
// The Segment Editor's effects that need no view: each takes masks (and the volume or its
// grid) and returns the new mask; Segmentation::setMask makes it one undo step.

#include <cstddef>

#include <glm/glm.hpp>

#include "core/segmentation/SegmentMask.h"
#include "core/volume/Volume.h"

namespace lucent {

// Voxels with lo <= value <= hi (HU for CT).
SegmentMask thresholdMask(const Volume& volume, double lo, double hi);

// Islands: sets of voxels joined through shared faces (6-connectivity, as Slicer's Islands
// effect by default).
struct Island {
    std::size_t voxels = 0;
    std::size_t first = 0; // its lowest voxel index
};
// Every island of the mask with its voxel count, largest first (ties: lowest first voxel).
std::vector<Island> islandsOf(const SegmentMask& mask);
SegmentMask keepLargestIsland(const SegmentMask& mask);
// Removes the islands smaller than minMm3 (voxel count times the voxel volume).
SegmentMask removeSmallIslands(const SegmentMask& mask, const VolumeGeometry& grid, double minMm3);
// The island that holds `voxel` alone (empty when the voxel is not set).
SegmentMask keepIslandAt(const SegmentMask& mask, const glm::ivec3& voxel);

// Margin: mm > 0 grows the mask by every voxel whose centre lies within mm of a set voxel's
// centre; mm < 0 shrinks it, keeping the set voxels farther than |mm| from every unset
// voxel's centre (voxels outside the grid count as unset). Exact Euclidean distances in mm
// with the grid's spacing (anisotropic voxels too).
SegmentMask marginMask(const SegmentMask& mask, const VolumeGeometry& grid, double mm);

// Hollow: a shell of `thicknessMm` inside the mask's surface (the mask minus its shrink).
SegmentMask hollowMask(const SegmentMask& mask, const VolumeGeometry& grid, double thicknessMm);

} // namespace lucent
