#pragma once
// Internal to core/segdicom: which image of a series each slice of its volume's grid is.

#include <vector>

#include <glm/glm.hpp>

#include "core/report/ReferencedSeries.h"
#include "core/volume/Volume.h"

namespace lucent::segdicom {

// The slice k of `grid` whose first voxel centre is `position` (within a tenth of a voxel
// on each axis), or -1 when none is.
int sliceAt(const VolumeGeometry& grid, const glm::dvec3& position);

// For each slice k of `grid`, the single-frame image of `series` that lies there (nullptr
// where none does: a resampled or tilted volume).
std::vector<const ReferencedImage*> imagesBySlice(const ReferencedSeries& series,
                                                  const VolumeGeometry& grid);

// True when the rows and columns of an image plane run along the grid's i and j axes.
bool sameOrientation(const VolumeGeometry& grid, const glm::dvec3& rowDir,
                     const glm::dvec3& colDir);

} // namespace lucent::segdicom
