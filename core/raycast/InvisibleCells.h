#pragma once
// Trilinear cells that no sample can see: one bit per cell, so that the packet
// kernel passes over a sample with one load where it would read eight voxels.
// Private to core/raycast.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {

// One bit per cell, set where all eight voxels of the cell whose lowest corner
// is voxel (i, j, k) lie below lo, or all above hi. A trilinear sample in such
// a cell lies between its lowest and highest voxel (up to float rounding,
// which the caller's margin covers), so it is below lo or above hi as well.
// Cells on the last voxel of an axis are never set: samples there are clamped
// into the cell before it and may lie a rounding error outside it.
//
// The bits of each block of 8 x 8 x 8 cells fill one 64-byte cache line, x
// fastest: a ray passes through a line per block, not a line per row.
struct InvisibleCells {
    std::vector<std::uint32_t> words; // 16 per block
    glm::ivec3 blocks{0};             // per axis

    // The word holding cell c's bit, and the bit.
    static std::size_t wordOf(glm::ivec3 c, glm::ivec3 blocks) {
        const std::size_t block =
            std::size_t(c.x >> 3) +
            std::size_t(blocks.x) *
                (std::size_t(c.y >> 3) + std::size_t(blocks.y) * std::size_t(c.z >> 3));
        return block * 16 + std::size_t(((c.y & 7) >> 2) + 2 * (c.z & 7));
    }
    static int bitOf(glm::ivec3 c) { return (c.x & 7) + 8 * (c.y & 3); }

    bool contains(glm::ivec3 c) const { return (words[wordOf(c, blocks)] >> bitOf(c) & 1u) != 0; }
};

InvisibleCells findInvisibleCells(const Volume& volume, double lo, double hi);

} // namespace lucent
