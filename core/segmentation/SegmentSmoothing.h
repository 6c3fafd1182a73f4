#pragma once
// The Segment Editor's smoothing: a median filter and a morphological closing of a mask,
// each with its size in mm (as Slicer's Smoothing effect offers them).

#include "core/segmentation/SegmentMask.h"
#include "core/volume/Volume.h"

namespace lucent {

// Median: each voxel takes the lower median of the mask over a box centred on it, per axis
// the odd number of voxels nearest to kernelMm / spacing (at least 1, at most 31). Only the
// box's voxels inside the grid count, so a segment touching the border is not eaten away:
// the voxel is set where more than half of them are set.
SegmentMask medianMask(const SegmentMask& mask, const VolumeGeometry& grid, double kernelMm);

// Per axis, the box size medianMask uses for `kernelMm`.
glm::ivec3 medianKernelVoxels(const VolumeGeometry& grid, double kernelMm);

// Closing with a ball of radius `radiusMm`: the mask grown by it, then shrunk by it
// (marginMask's exact Euclidean distances), as if the grid went on beyond its border with
// nothing set there. Fills gaps and holes narrower than the ball; never removes a voxel.
SegmentMask closingMask(const SegmentMask& mask, const VolumeGeometry& grid, double radiusMm);

} // namespace lucent
