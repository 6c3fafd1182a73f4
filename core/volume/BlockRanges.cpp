#include "core/volume/BlockRanges.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lucent {

BlockRanges::BlockRanges(const Volume& volume) {
    const glm::ivec3 dims = volume.dims();
    blocks_ = (dims + kBlockSize - 1) / kBlockSize;
    const std::size_t count = std::size_t(blocks_.x) * std::size_t(blocks_.y) * blocks_.z;
    lo_.assign(count, 0.0f);
    hi_.assign(count, 0.0f);
    visitVoxels(volume, [&](auto voxels) {
        constexpr float kInf = std::numeric_limits<float>::infinity();
#pragma omp parallel for schedule(dynamic, 1)
        for (int bz = 0; bz < blocks_.z; ++bz) {
            const int z0 = bz * kBlockSize, z1 = std::min(z0 + kBlockSize, dims.z - 1);
            for (int by = 0; by < blocks_.y; ++by) {
                const int y0 = by * kBlockSize, y1 = std::min(y0 + kBlockSize, dims.y - 1);
                for (int bx = 0; bx < blocks_.x; ++bx) {
                    const int x0 = bx * kBlockSize, x1 = std::min(x0 + kBlockSize, dims.x - 1);
                    float lo = kInf, hi = -kInf;
                    bool nan = false;
                    for (int z = z0; z <= z1; ++z) {
                        for (int y = y0; y <= y1; ++y) {
                            const auto* row = voxels.data() + volume.linearIndex(0, y, z);
                            for (int x = x0; x <= x1; ++x) {
                                const float v = float(row[x]);
                                nan = nan || std::isnan(v);
                                lo = std::min(lo, v);
                                hi = std::max(hi, v);
                            }
                        }
                    }
                    const std::size_t id = idOf({bx, by, bz});
                    lo_[id] = nan ? -kInf : lo;
                    hi_[id] = nan ? kInf : hi;
                }
            }
        }
    });
}

} // namespace lucent
