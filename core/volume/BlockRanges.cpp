#include "core/volume/BlockRanges.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace lucent {

BlockRanges::BlockRanges(const Volume& volume) {
    const glm::ivec3 dims = volume.dims();
    blocks_ = (dims + kBlockSize - 1) / kBlockSize;
    const std::size_t count = std::size_t(blocks_.x) * std::size_t(blocks_.y) * blocks_.z;
    lo_.assign(count, 0.0f);
    hi_.assign(count, 0.0f);
    constexpr float kInf = std::numeric_limits<float>::infinity();
    const auto last = [](int block, int n) {
        return std::min(block * kBlockSize + kBlockSize, n - 1);
    };
    visitVoxels(volume, [&](auto voxels) {
        using T = typename decltype(voxels)::value_type;
        // Per slab of blocks along z: each row's blocks along x over the
        // slab's slices (sequential reads), then the rows of each block.
#pragma omp parallel
        {
            const std::size_t slabSize = std::size_t(blocks_.x) * std::size_t(dims.y);
            std::vector<float> slabLo(slabSize), slabHi(slabSize);
#pragma omp for schedule(dynamic, 1)
            for (int bz = 0; bz < blocks_.z; ++bz) {
                std::fill(slabLo.begin(), slabLo.end(), kInf);
                std::fill(slabHi.begin(), slabHi.end(), -kInf);
                for (int z = bz * kBlockSize; z <= last(bz, dims.z); ++z) {
                    for (int y = 0; y < dims.y; ++y) {
                        const T* row = voxels.data() + volume.linearIndex(0, y, z);
                        float* lo = slabLo.data() + std::size_t(y) * std::size_t(blocks_.x);
                        float* hi = slabHi.data() + std::size_t(y) * std::size_t(blocks_.x);
                        for (int bx = 0; bx < blocks_.x; ++bx) {
                            T a = row[bx * kBlockSize], b = a;
                            bool nan = false;
                            for (int x = bx * kBlockSize + 1; x <= last(bx, dims.x); ++x) {
                                a = std::min(a, row[x]);
                                b = std::max(b, row[x]);
                                if constexpr (std::is_floating_point_v<T>) {
                                    nan = nan || std::isnan(row[x]);
                                }
                            }
                            if constexpr (std::is_floating_point_v<T>) {
                                nan = nan || std::isnan(row[bx * kBlockSize]);
                            }
                            lo[bx] = nan ? -kInf : std::min(lo[bx], float(a));
                            hi[bx] = nan ? kInf : std::max(hi[bx], float(b));
                        }
                    }
                }
                for (int by = 0; by < blocks_.y; ++by) {
                    for (int bx = 0; bx < blocks_.x; ++bx) {
                        float a = kInf, b = -kInf;
                        for (int y = by * kBlockSize; y <= last(by, dims.y); ++y) {
                            const std::size_t at =
                                std::size_t(y) * std::size_t(blocks_.x) + std::size_t(bx);
                            a = std::min(a, slabLo[at]);
                            b = std::max(b, slabHi[at]);
                        }
                        const std::size_t id = idOf({bx, by, bz});
                        lo_[id] = a;
                        hi_[id] = b;
                    }
                }
            }
        }
    });
}

} // namespace lucent
