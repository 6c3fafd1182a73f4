#pragma once
// Which voxels of each brick a render can read: the box of its cells whose
// values the transfer function and clip box leave visible ("tight bricks").
// Bricks and cells are those of level 0; a brick drawn from a coarser level
// decides visibility from that level's cells, whose ranges cover what its
// filters read there. No GL: the GPU pool uploads the boxes given here.

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/volume/BrickGrid.h"

namespace lucent {

// Level voxels a sample at q reads around floor(q): from floor(q) - below to
// floor(q) + above. Trilinear (and nearest, and pre-classification) reads
// 0 and 1; gradients by central differences and the cubic B-spline read 1 and
// 2; filterReach adds a guard texel on each side for the GPU's rounding.
struct FilterReach {
    int below = 0;
    int above = 1;
};
FilterReach filterReach(bool cubic, bool differencesInShader);

// A brick's box of level-0 samples [lo, hi), and whether any of its cells can
// contribute (else it is kept only so that rays read its border: a
// pre-integrated segment or an isosurface crossing that starts there).
struct SampleBox {
    glm::ivec3 lo{0}, hi{0};
    bool contributes = true;
};

// The level's voxels a box's samples read, [lo, lo + size).
struct StoredBox {
    glm::ivec3 lo{0}, size{0};
};
// Level n's position of level-0 p: (p - (2^n - 1) / 2) / 2^n (LodPyramid).
StoredBox storedBox(const SampleBox& box, int level, FilterReach reach);

class BrickBoxes {
public:
    // The level-0 volume's dims, its bricks and its leaping cells (sizes in voxels).
    BrickBoxes(glm::ivec3 dims, int brickSize, int cellSize);

    int brickSize() const { return brickSize_; }
    glm::ivec3 cellsPerAxis() const { return cellsPer_; }
    glm::ivec3 bricksPerAxis() const { return bricksPer_; }
    std::size_t cellCount() const;
    std::size_t brickCount() const;
    // A brick's position in the grid of bricks from its id (x fastest).
    glm::ivec3 brickIndex(std::size_t id) const;
    std::uint32_t brickOfCell(glm::ivec3 cell) const; // of its first voxel
    std::uint32_t brickOfLastVoxel(glm::ivec3 cell) const;

    // The cell of `levelCells` (a grid of `level`'s cells) that holds each
    // level-0 cell's centre: its value range covers every read of a sample
    // in that level-0 cell at that level (the cells' overlap >= 3).
    std::vector<std::uint32_t> levelCellOf(const BrickGrid& levelCells, int level) const;
    // Per level-0 cell: 1 where the clip box meets it and `visible` says its
    // range (at `level`, through levelCellOf) can show.
    std::vector<std::uint8_t> visibleCells(const BrickGrid& levelCells, int level,
                                           const std::function<bool(double, double)>& visible,
                                           const ClipBox& clip) const;
    // Per brick, the box of its visible cells (clipped to its core), or
    // nothing. withNeighbours: the cells next to visible ones (26 around)
    // count too, so that rays read the values just before a visible cell.
    std::vector<std::optional<SampleBox>> boxes(const std::vector<std::uint8_t>& cells,
                                                bool withNeighbours) const;

private:
    glm::ivec3 dims_;
    int brickSize_, cellSize_;
    glm::ivec3 cellsPer_, bricksPer_;
};

} // namespace lucent
