#pragma once
// Trilinear cells that no sample can see, and how far around them that holds:
// the fast kernels pass over such samples with one load where they would read
// eight voxels, and over several at once where the ray cannot leave the cells
// nobody sees. Private to core/raycast.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {

// Per trilinear cell (the cell whose lowest corner is voxel (i, j, k)), its
// clearance: 0 where a sample in it may be visible; 1 where all eight of its
// voxels lie below lo, or all above hi; 2 where that holds for every cell
// within one cell of it (chessboard distance), 3 within two. A trilinear
// sample lies between its cell's lowest and highest voxel (up to float
// rounding, which the caller's margin covers), so it is below lo or above hi
// as well, and a ray that stays within r cells of a cell of clearance r + 1
// sees nothing. Cells on the last voxel of an axis are 0: samples there are
// clamped into the cell before it and may lie a rounding error outside it.
//
// Two bits per cell; the 8 x 8 x 8 cells of a block fill two 64-byte cache
// lines, x fastest: a ray reads a line per half block, not one per row.
struct InvisibleCells {
    std::vector<std::uint32_t> words; // 32 per block
    glm::ivec3 blocks{0};             // per axis

    // The word holding cell c's clearance, and its shift in the word.
    static std::size_t wordOf(glm::ivec3 c, glm::ivec3 blocks) {
        const std::size_t block =
            std::size_t(c.x >> 3) +
            std::size_t(blocks.x) *
                (std::size_t(c.y >> 3) + std::size_t(blocks.y) * std::size_t(c.z >> 3));
        return block * 32 + std::size_t(((c.y & 7) + 8 * (c.z & 7)) >> 1);
    }
    static int shiftOf(glm::ivec3 c) { return 2 * (c.x & 7) + 16 * (c.y & 1); }

    int clearance(glm::ivec3 c) const { return int(words[wordOf(c, blocks)] >> shiftOf(c) & 3u); }
};

InvisibleCells findInvisibleCells(const Volume& volume, double lo, double hi);

} // namespace lucent
