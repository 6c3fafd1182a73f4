#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {

// One brick of a BrickGrid. Voxel ranges are half-open, in index space.
struct Brick {
    glm::ivec3 index{0}; // position in the grid of bricks
    glm::ivec3 first{0}; // core voxel range [first, last), without overlap
    glm::ivec3 last{0};
    float minValue = 0.0f; // over the core range plus the overlap (clamped to
    float maxValue = 0.0f; // the volume): what a sample or gradient in the brick can read
};

// A volume split into bricks of brickSize^3 voxels (smaller at the far edges
// where the dimensions are not multiples of brickSize), each padded by
// `overlap` voxels on every side for interpolation and gradients. Bricks are
// stored x fastest: id = ix + nx * (iy + ny * iz). The CPU and GPU renderers
// share this structure. NaN voxels are ignored by min/max; a brick holding
// only NaN has minValue = +inf and maxValue = -inf.
class BrickGrid {
public:
    // Computes every brick's min/max in one parallel pass over the voxels.
    // Throws std::invalid_argument for brickSize < 1 or overlap < 0. An empty
    // volume gives an empty grid.
    explicit BrickGrid(const Volume& volume, int brickSize = 64, int overlap = 3);

    int brickSize() const { return brickSize_; }
    int overlap() const { return overlap_; }
    const glm::ivec3& volumeDims() const { return dims_; }
    glm::ivec3 bricksPerAxis() const { return perAxis_; }
    const std::vector<Brick>& bricks() const { return bricks_; }
    std::size_t count() const { return bricks_.size(); }
    // Throws std::out_of_range for an index outside the grid.
    const Brick& brickAt(glm::ivec3 index) const;
    std::uint32_t idOf(glm::ivec3 index) const;

    // The voxel range [paddedFirst, paddedLast) a brick holds: its core range
    // grown by the overlap, clamped to the volume.
    glm::ivec3 paddedFirst(const Brick& brick) const;
    glm::ivec3 paddedLast(const Brick& brick) const;

private:
    int brickSize_;
    int overlap_;
    glm::ivec3 dims_{0};
    glm::ivec3 perAxis_{0};
    std::vector<Brick> bricks_;
};

// Box in index space (continuous voxel coordinates, inclusive) that limits
// what is drawn. The default box holds everything; lo > hi on an axis holds
// nothing.
struct ClipBox {
    glm::dvec3 lo{-1e300};
    glm::dvec3 hi{1e300};
    bool operator==(const ClipBox&) const = default;
};

// Ids of the bricks that can contribute to an image, ascending: those whose
// value range [minValue, maxValue] is visible (isVisible(lo, hi) says whether
// any value in [lo, hi] has non-zero opacity) and whose padded box of voxel
// centres [paddedFirst, paddedLast - 1] meets the clip box (closed intervals).
std::vector<std::uint32_t> visibleBricks(const BrickGrid& grid,
                                         const std::function<bool(double lo, double hi)>& isVisible,
                                         const ClipBox& clip);

} // namespace lucent
