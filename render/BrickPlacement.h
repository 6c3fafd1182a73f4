#pragma once
// Where a frame's bricks go in the atlas: the boxes still missing placed in
// the room the pool has (least recently used boxes evicted), and where they
// do not fit, a new atlas packed largest first with the resident boxes copied
// over on the GPU. Private to render/.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "render/BrickPool.h"

namespace lucent {

// The boxes did not pack into an atlas within the budget.
struct PackingError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::size_t volumeOf(glm::ivec3 size);

// What a frame draws of one octree node: its level and id, the box of its
// level's voxels, whether that box must be uploaded.
struct Shown {
    int level = -1; // -1: not shown
    std::uint32_t id = 0;
    StoredBox stored;
    bool upload = false;
};

using Placements = std::vector<std::pair<std::size_t, glm::ivec3>>; // shown index, atlas origin

// The atlas origin of every shown box marked for upload; repacks the pool
// into a new atlas (within `budget` bytes) where the current one has no room.
// Throws PackingError when even a new atlas cannot hold them.
Placements placeUploads(std::unique_ptr<BrickPool>& pool, const std::vector<Shown>& shown,
                        std::size_t budget, std::uint64_t frame);

} // namespace lucent
