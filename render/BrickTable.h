#pragma once
// What the shader reads about each brick and each leaping cell, as arrays
// (SceneTextures uploads them): per level-0 brick, where its box sits in the
// atlas, at which level, and which samples it backs; per level-0 cell, whether
// rays leap over it and the range of values it can give. No GL here.

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/volume/BrickBoxes.h"
#include "render/BrickPool.h"

namespace lucent {

struct BrickTable {
    int brickSize = 0; // of the pages: the pool's bricks (BrickStreamer)
    glm::ivec3 bricksPerAxis{0}, cellsPerAxis{0};
    // Per brick: xyz the atlas texel of its level's voxel (0, 0, 0), so that
    // texel = xyz + level position; w = state | level << 2, state 0 absent,
    // 1 resident, 2 resident only for its border (rays leap over it).
    std::vector<glm::ivec4> page;
    // Per brick: its sample box [lo, hi) in level-0 voxels, 16 bits each
    // (x = lo.x | lo.y << 16, y = lo.z | hi.x << 16, z = hi.y | hi.z << 16, w = 0).
    std::vector<glm::uvec4> box;
    // Per cell: 2 leap the brick, 1 leap the cell, 0 sample it; its value
    // range at the level its brick is drawn from (a margin for the spline).
    std::vector<std::uint8_t> codes;
    std::vector<glm::vec2> ranges;
    // Bricks shown per level.
    std::vector<std::size_t> perLevel;

    bool operator==(const BrickTable&) const = default;
    std::size_t bytes() const; // on the GPU: page, boxes, codes, ranges
};

struct ShownBrick {
    const BrickPool::Entry* entry = nullptr; // null: absent
    SampleBox box;
};

struct CellRanges {
    const BrickGrid* cells = nullptr;               // the level's cells
    const std::vector<std::uint32_t>* at = nullptr; // level-0 cell -> level cell (levelCellOf)
};

// `shown` per level-0 brick; `levels` per level. decides (DVR, iso): codes
// from visibility; otherwise (MIP, MinIP, average) only absent bricks are leapt.
BrickTable makeBrickTable(const BrickBoxes& boxes, const std::vector<ShownBrick>& shown,
                          const std::vector<CellRanges>& levels,
                          const std::function<bool(double, double)>& visible, bool decides,
                          bool cubic);

} // namespace lucent
