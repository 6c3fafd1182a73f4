#pragma once
// What the Segment Editor's paint, erase and draw effects do to a mask, in patient mm:
// a brush (a sphere, or its disc on one slice) and a closed outline filled on a slice.

#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/segmentation/SegmentMask.h"
#include "core/volume/Volume.h"

namespace lucent {

// A slice of a view: the voxels whose centre lies within (-halfThickness, +halfThickness]
// of the plane along its unit normal (half a slice step: one voxel layer).
struct SliceSlab {
    glm::dvec3 normal{0.0, 0.0, 1.0};
    double halfThicknessMm = 0.5;
};

// Sets (on) or clears every voxel whose centre lies within radiusMm of `centre` (LPS mm);
// with `slab`, only those of the slice through `centre`. Returns how many voxels it changed.
std::size_t paintBrush(SegmentMask& mask, const VolumeGeometry& grid, const glm::dvec3& centre,
                       double radiusMm, bool on, const std::optional<SliceSlab>& slab = {});

// Sets (on) or clears the voxels of the slice through outline[0] whose centre, projected on
// the slice, lies inside the closed outline (points in LPS mm on the slice, the last joined
// to the first; even-odd rule). Fewer than 3 points change nothing. Returns the count changed.
std::size_t fillOutline(SegmentMask& mask, const VolumeGeometry& grid,
                        const std::vector<glm::dvec3>& outline, const SliceSlab& slab,
                        bool on = true);

} // namespace lucent
