#pragma once
// Which level of detail each part of a volume is drawn from under a memory
// budget: an octree of bricks, where a brick of level n covers 2x2x2 bricks
// of level n - 1 (the same number of its own, coarser, voxels). Starting from
// the coarsest level, the refinement worth most for the bytes it adds
// (projected voxel size, what the brick shows, how near the centre of the
// image it is) comes first while it fits, so that a tight budget coarsens the
// bricks that matter least instead of the whole volume.

#include <cstddef>
#include <string>
#include <vector>

namespace lucent {

struct LodNode {
    int level = 0;
    std::size_t bytes = 0; // its box at its level; 0 where it shows nothing there
    double worth = 0.0;    // of drawing it from finer voxels (> 0), before its level's factor
    std::vector<std::size_t> children; // nodes of level - 1 within it
};

enum class LodPolicy {
    PerBrick, // every brick as fine as the budget allows, the most worth first
    Uniform,  // the finest level whose bricks all fit, for all of them
};

struct LevelChoice {
    std::vector<std::size_t> shown; // the nodes drawn: they cover every root once
    std::size_t bytes = 0;          // in all
    std::string coarsened;          // why not everything is at level 0 ("" when it is)
};

// roots: the nodes of the coarsest level. Throws BudgetError (BrickResidency.h)
// when even they exceed the budget, naming what they need.
LevelChoice chooseLevels(const std::vector<LodNode>& nodes, const std::vector<std::size_t>& roots,
                         std::size_t budget, LodPolicy policy);

} // namespace lucent
