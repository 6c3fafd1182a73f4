#include "core/segmentation/SegmentEffects.h"

#include <algorithm>
#include <array>

namespace lucent {
namespace {

// Floods the island of `start` (set in mask, not yet visited): marks it visited, clears it
// in `clear` and sets it in `copy` when given. Returns its voxel count.
std::size_t flood(const SegmentMask& mask, std::size_t start, SegmentMask& visited,
                  SegmentMask* clear, SegmentMask* copy) {
    static constexpr std::array<glm::ivec3, 6> kFaces{
        {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
    std::vector<std::size_t> stack{start};
    visited.set(start);
    std::size_t count = 0;
    while (!stack.empty()) {
        const std::size_t at = stack.back();
        stack.pop_back();
        ++count;
        if (clear != nullptr) {
            clear->set(at, false);
        }
        if (copy != nullptr) {
            copy->set(at);
        }
        const glm::ivec3 v = mask.voxelOf(at);
        for (const glm::ivec3& d : kFaces) {
            const glm::ivec3 n = v + d;
            if (!mask.inside(n)) {
                continue;
            }
            const std::size_t ni = mask.linearIndex(n.x, n.y, n.z);
            if (mask.get(ni) && !visited.get(ni)) {
                visited.set(ni);
                stack.push_back(ni);
            }
        }
    }
    return count;
}

} // namespace

SegmentMask thresholdMask(const Volume& volume, double lo, double hi) {
    SegmentMask mask(volume.dims());
    visitVoxels(volume, [&](auto voxels) {
        for (std::size_t i = 0; i < voxels.size(); ++i) {
            const double v = static_cast<double>(voxels[i]);
            if (v >= lo && v <= hi) {
                mask.set(i);
            }
        }
    });
    return mask;
}

std::vector<Island> islandsOf(const SegmentMask& mask) {
    SegmentMask visited(mask.dims());
    std::vector<Island> islands;
    mask.forEachSet([&](std::size_t i) {
        if (!visited.get(i)) {
            islands.push_back({flood(mask, i, visited, nullptr, nullptr), i});
        }
    });
    std::stable_sort(islands.begin(), islands.end(),
                     [](const Island& a, const Island& b) { return a.voxels > b.voxels; });
    return islands;
}

SegmentMask keepLargestIsland(const SegmentMask& mask) {
    const std::vector<Island> islands = islandsOf(mask);
    SegmentMask out(mask.dims());
    if (!islands.empty()) {
        SegmentMask visited(mask.dims());
        flood(mask, islands.front().first, visited, nullptr, &out);
    }
    return out;
}

SegmentMask removeSmallIslands(const SegmentMask& mask, const VolumeGeometry& grid, double minMm3) {
    const double voxelMm3 = grid.spacing.x * grid.spacing.y * grid.spacing.z;
    SegmentMask out = mask;
    SegmentMask visited(mask.dims());
    for (const Island& island : islandsOf(mask)) {
        if (static_cast<double>(island.voxels) * voxelMm3 < minMm3) {
            flood(mask, island.first, visited, &out, nullptr);
        }
    }
    return out;
}

SegmentMask keepIslandAt(const SegmentMask& mask, const glm::ivec3& voxel) {
    SegmentMask out(mask.dims());
    if (mask.inside(voxel) && mask.at(voxel.x, voxel.y, voxel.z)) {
        SegmentMask visited(mask.dims());
        flood(mask, mask.linearIndex(voxel.x, voxel.y, voxel.z), visited, nullptr, &out);
    }
    return out;
}

SegmentMask hollowMask(const SegmentMask& mask, const VolumeGeometry& grid, double thicknessMm) {
    SegmentMask out = mask;
    return out.subtract(marginMask(mask, grid, -std::abs(thicknessMm)));
}

} // namespace lucent
