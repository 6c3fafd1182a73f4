#pragma once
// Trilinear cells that no sample can see: one bit per cell, so that the packet
// kernel passes over a sample with one load where it would read eight voxels.
// Private to core/raycast.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {

// Bit i % 32 of words[rowWords * (j + ny * k) + i / 32] is set where all eight
// voxels of the cell whose lowest corner is voxel (i, j, k) lie below lo, or
// all above hi. A trilinear sample in such a cell lies between its lowest and
// highest voxel (up to float rounding, which the caller's margin covers), so
// it is below lo or above hi as well. Cells on the last voxel of an axis are
// never set: samples there are clamped into the cell before it and may lie a
// rounding error outside it.
struct InvisibleCells {
    std::vector<std::uint32_t> words;
    int rowWords = 0;
    int ny = 0;

    bool contains(glm::ivec3 c) const {
        const std::size_t row = std::size_t(c.y) + std::size_t(ny) * std::size_t(c.z);
        return (words[row * std::size_t(rowWords) + std::size_t(c.x / 32)] >> (c.x % 32) & 1u) != 0;
    }
};

InvisibleCells findInvisibleCells(const Volume& volume, double lo, double hi);

} // namespace lucent
