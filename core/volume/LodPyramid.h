#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {

// A volume and its coarser levels: level n+1 averages 2x2x2 voxels of level n
// (a lone last voxel where a dimension is odd), keeps the voxel type (integers
// rounded) and is placed where those voxels' centres are. Level 0 is the
// volume itself, not copied. Coarser levels stop once every dimension is at
// most `smallest` voxels, or at `maxLevels` levels.
class LodPyramid {
public:
    explicit LodPyramid(const Volume& base, int smallest = 16, int maxLevels = 8);

    int levelCount() const { return static_cast<int>(coarser_.size()) + 1; }
    // Throws std::out_of_range for a level that is not there.
    const Volume& level(int n) const;

    // Continuous index p0 of level 0 to that of level n: (p0 - (2^n - 1) / 2) / 2^n.
    static glm::dvec3 fromLevel0(const glm::dvec3& p0, int n);
    static glm::dvec3 toLevel0(const glm::dvec3& pn, int n);

private:
    const Volume& base_;
    std::vector<std::unique_ptr<Volume>> coarser_;
};

// One level coarser: exposed for the tests and for callers that need a single level.
Volume downsampleByTwo(const Volume& volume);

} // namespace lucent
