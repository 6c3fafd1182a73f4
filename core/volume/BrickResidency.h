#pragma once
// What the GPU keeps of a bricked volume, decided without any GL: which bricks
// of which level a render needs within a budget of pool slots, which slot
// each one occupies, and the voxels a slot holds. The GPU brick pool applies
// these decisions; the tests check them on their own.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "core/volume/BrickGrid.h"

namespace lucent {

// Not even the coarsest level's needed bricks fit the pool.
class BudgetError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct ResidencyPlan {
    int level = 0;
    // Ids in that level's grid, ascending: the bricks that can contribute, and
    // (when asked for) their neighbours, which rays leap over but read at the
    // border (isosurface crossings, pre-integrated segments).
    std::vector<std::uint32_t> bricks;
    std::vector<std::uint8_t> leapable; // per entry of bricks: 1 for a neighbour only
    std::size_t needed = 0;             // bricks that can contribute
    // Per finer level that did not fit, the bricks it would have needed.
    std::vector<std::size_t> rejected;
};

// levels: the brick grids of the LOD levels, finest first (level n's voxel
// p_n = (p_0 - (2^n - 1) / 2) / 2^n). The finest level whose bricks fit
// `slots` wins. isVisible and clip (in level-0 index space) as for
// visibleBricks. inView, when given, says whether a box of voxel centres
// (level-0 index space, closed) can be seen at all: bricks outside the view
// are not needed. Throws BudgetError when no level fits, naming the smallest need.
using BoxTest = std::function<bool(const glm::dvec3& lo, const glm::dvec3& hi)>;
ResidencyPlan planResidency(const std::vector<const BrickGrid*>& levels,
                            const std::function<bool(double lo, double hi)>& isVisible,
                            const ClipBox& clip, bool withNeighbours, std::size_t slots,
                            const BoxTest& inView = {});

// The slots of a brick pool: which brick (level and id) sits in which slot.
// A render's bricks are made resident together; bricks it does not use stay
// until their slot is needed, least recently used first, so turning back to
// an earlier transfer function uploads nothing.
class BrickSlots {
public:
    struct Upload {
        std::uint64_t key;
        std::uint32_t slot;
    };
    explicit BrickSlots(std::size_t capacity) : capacity_(capacity) {}
    static std::uint64_t key(int level, std::uint32_t brick) {
        return (std::uint64_t(std::uint32_t(level)) << 32) | brick;
    }

    // Makes every key resident and returns those that were not, with the slot
    // to upload each into. Throws std::length_error when there are more keys
    // than slots (the plan must fit first).
    std::vector<Upload> acquire(const std::vector<std::uint64_t>& keys);
    std::optional<std::uint32_t> slotOf(std::uint64_t key) const;
    std::size_t capacity() const { return capacity_; }
    std::size_t resident() const { return slotOfKey_.size(); } // slots 0 .. resident-1
    // The same bricks in the same slots, with room for more. Throws
    // std::length_error when the capacity would not hold them.
    BrickSlots withCapacity(std::size_t capacity) const;

private:
    std::size_t capacity_;
    std::uint64_t clock_ = 0;
    std::unordered_map<std::uint64_t, std::uint32_t> slotOfKey_;
    std::vector<std::uint64_t> keyOfSlot_; // per allocated slot
    std::vector<std::uint64_t> lastUse_;   // per allocated slot
};

// Beyond the volume's edge a slot repeats the edge voxel (what trilinear
// sampling clamps to) or mirrors about it (the B-spline coefficients' boundary).
enum class BrickEdge { Clamp, Mirror };

// Copies the slotSize^3 voxels that start `overlap` voxels before the brick's
// core (`first`) into out (x fastest). T: int16_t, uint16_t or float.
template <class T>
void extractBrick(const T* data, glm::ivec3 dims, glm::ivec3 first, int overlap, int slotSize,
                  BrickEdge edge, T* out);

// The gradient of the same block: half the difference of the two neighbours
// along each axis (indices clamped to the volume), divided by `unit` and
// rounded to int16, four per voxel (x, y, z, 0). Trilinear interpolation of
// these gives the central differences of the trilinear field one voxel apart
// (what the ray casters shade with), up to rounding, except on the outermost
// voxels. unit = (max - min) / 2 / 32767 keeps every component in range.
template <class T>
void extractGradientBrick(const T* data, glm::ivec3 dims, glm::ivec3 first, int overlap,
                          int slotSize, double unit, std::int16_t* out);

} // namespace lucent
