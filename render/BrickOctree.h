#pragma once
// The octree of a frame's pages over the levels it may draw from: a node of
// level n is a brick of that level covering 2^n pages a side, with the union
// of its pages' boxes at its level and what refining it is worth (its pages'
// most). chooseLevels (core/volume/BrickLevels.h) picks the nodes drawn.
// Private to render/.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "core/volume/BrickBoxes.h"
#include "core/volume/BrickLevels.h"

namespace lucent {

class BrickOctree {
public:
    struct Node {
        int level = 0;
        std::uint32_t id = 0;         // in its level's grid of nodes
        std::optional<SampleBox> box; // the union of its pages' boxes at its level
        double worth = 0.0;
    };

    // boxes[level][page]: the page's box at that level (none: nothing to
    // show there or out of view); worth per page.
    BrickOctree(const BrickBoxes& pages,
                const std::vector<std::vector<std::optional<SampleBox>>>& boxes,
                const std::vector<double>& worth);

    const std::vector<Node>& nodes() const { return nodes_; }
    int levels() const { return int(nodesPer_.size()); }
    // Whether a page has a box at any level (the others take no node).
    bool hasPage(std::uint32_t page) const { return anyBox_[page] != 0; }
    // The node of a page (hasPage) at a level.
    std::size_t nodeOf(std::uint32_t page, int level) const;
    // The node of `node`'s pages at a coarser level, if any.
    std::optional<std::size_t> ancestor(const Node& node, int level) const;
    // The levels to draw within `budget` bytes, each node's box stored with
    // `reach` at `texelBytes` a voxel. Throws BudgetError (BrickResidency.h).
    LevelChoice choose(FilterReach reach, std::size_t texelBytes, std::size_t budget,
                       LodPolicy policy) const;

private:
    const BrickBoxes& pages_;
    std::vector<Node> nodes_;
    std::vector<std::map<std::uint32_t, std::size_t>> nodeAt_; // per level: id -> node
    std::vector<glm::ivec3> nodesPer_;
    std::vector<char> anyBox_;
};

} // namespace lucent
