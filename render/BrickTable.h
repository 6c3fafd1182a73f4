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
    // Per brick, what the shader reads in one texel fetch (pageEntry): the
    // page and its sample box [lo, hi) in level-0 voxels, the box from the
    // brick's first voxel b * brickSize.
    std::vector<glm::uvec4> entries;
    // Per cell: 2 leap the brick, 1 leap the cell, 0 sample it; its value
    // range at the level its brick is drawn from (a margin for the spline).
    std::vector<std::uint8_t> codes;
    std::vector<glm::vec2> ranges;
    // Bricks shown per level.
    std::vector<std::size_t> perLevel;

    bool operator==(const BrickTable&) const = default;
    std::size_t bytes() const; // on the GPU: page, boxes, codes, ranges
};

// The largest brick a page entry describes (its box in 10 bits an axis).
inline constexpr int kMaxPageBrickSize = 1023;

// A brick's page entry: x = slot.x | slot.y << 16, y = slot.z | state << 16 |
// level << 18 (slot: page.xyz, 16-bit two's complement), z = the box's lo and
// w its hi from the brick's first voxel, 10 bits an axis (x lowest).
// Throws std::invalid_argument where a field does not fit (a slot beyond
// +-32767 texels, a box beyond 1023 voxels of the brick's first).
glm::uvec4 pageEntry(glm::ivec4 page, const SampleBox& box, glm::ivec3 brickFirst);

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
