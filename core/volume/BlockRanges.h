#pragma once
// The values each block of 2 x 2 x 2 voxels can give a sample: per block b,
// the range of the voxels [2b, 2b + 2] (clamped to the volume), which every
// trilinear or nearest sample at a position in [2b, 2b + 2) reads from. What
// the GPU ray caster passes over sample by sample, finer than its leaping
// cells (render/LeapTextures.h). Level 0 only; no GL here.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {

class BlockRanges {
public:
    static constexpr int kBlockSize = 2;

    // One pass over the volume (parallel). A block holding a NaN voxel has
    // the range (-inf, +inf): a sample there may read it.
    explicit BlockRanges(const Volume& volume);

    glm::ivec3 blocksPerAxis() const { return blocks_; }
    std::size_t count() const { return lo_.size(); }
    // Blocks x fastest, as the volume's voxels.
    std::size_t idOf(glm::ivec3 b) const {
        return std::size_t(b.x) +
               std::size_t(blocks_.x) * (std::size_t(b.y) + std::size_t(blocks_.y) * b.z);
    }
    // Whether every value block `id` can give lies below lo or every one above hi.
    bool outside(std::size_t id, float lo, float hi) const { return hi_[id] < lo || lo_[id] > hi; }

private:
    glm::ivec3 blocks_{0};
    std::vector<float> lo_, hi_;
};

} // namespace lucent
