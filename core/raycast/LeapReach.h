#pragma once
// How far empty-space leaps can reach: per leaping cell, the radius (in
// cells) of the cube of cells around it that can all be leapt. The CPU ray
// caster's leaps, and the GPU ray caster's distance maps (render/LeapTextures.h).

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

// leapable: per cell of a grid of `cells` cells (x fastest), non-zero where
// the cell can be leapt. Returns per cell r such that every cell within
// Chebyshev distance r (cells beyond the grid count as leapable) can be
// leapt: the distance to the nearest cell that cannot, less one, at most 254;
// 0 where the cell itself cannot be leapt (unused there).
std::vector<std::uint8_t> leapReach(const std::vector<std::uint8_t>& leapable, glm::ivec3 cells);

// leapReach at most `cap` (1..254), by `cap` erosions of the leapable cells
// with a 3x3x3 cube: faster than the exact transform where only a short
// reach is wanted over many cells.
std::vector<std::uint8_t> leapReachWithin(const std::vector<std::uint8_t>& leapable,
                                          glm::ivec3 cells, int cap);

} // namespace lucent
