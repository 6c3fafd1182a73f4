#pragma once
// Internal to the isosurface extractor: separable Gaussian smoothing of a
// voxel block into floats, so that a binary mask gives a smooth field to
// contour. Voxels beyond the block repeat the nearest face voxel.

#include <functional>
#include <vector>

#include "core/surface/VoxelBlock.h"

namespace lucent {

// sigma in voxels (> 0); the kernel reaches ceil(3 sigma) voxels either side.
// The result holds block.size voxels, x fastest and unpadded. Progress is
// reported on [from, to]; returns false when the hook asked to stop.
template <class T>
bool gaussianBlur(const VoxelBlock<T>& block, double sigma, std::vector<float>& out,
                  const std::function<bool(double)>& progress, double from, double to);

// The kernel reach, in voxels.
int gaussianRadius(double sigma);

} // namespace lucent
