#include "core/volume/LodPyramid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace lucent {

namespace {

template <class T> void averageBlocks(const T* src, glm::ivec3 n, T* dst, glm::ivec3 m) {
#pragma omp parallel for schedule(static)
    for (int k = 0; k < m.z; ++k) {
        // The fine voxels a coarse one averages: two per axis, one at an odd end.
        const int ks[2] = {2 * k, std::min(2 * k + 1, n.z - 1)};
        const int nk = ks[1] != ks[0] ? 2 : 1;
        for (int j = 0; j < m.y; ++j) {
            const int js[2] = {2 * j, std::min(2 * j + 1, n.y - 1)};
            const int nj = js[1] != js[0] ? 2 : 1;
            T* out = dst + std::size_t(m.x) * (std::size_t(j) + std::size_t(m.y) * k);
            for (int i = 0; i < m.x; ++i) {
                const int is[2] = {2 * i, std::min(2 * i + 1, n.x - 1)};
                const int ni = is[1] != is[0] ? 2 : 1;
                double sum = 0.0;
                for (int c = 0; c < nk; ++c) {
                    for (int b = 0; b < nj; ++b) {
                        const T* row = src + std::size_t(n.x) *
                                                 (std::size_t(js[b]) + std::size_t(n.y) * ks[c]);
                        for (int a = 0; a < ni; ++a) {
                            sum += double(row[is[a]]);
                        }
                    }
                }
                const double mean = sum / double(ni * nj * nk);
                if constexpr (std::is_floating_point_v<T>) {
                    out[i] = T(mean);
                } else {
                    out[i] = T(std::lround(mean));
                }
            }
        }
    }
}

} // namespace

Volume downsampleByTwo(const Volume& volume) {
    const VolumeGeometry& g = volume.geometry();
    VolumeGeometry h = g;
    h.dims = (g.dims + 1) / 2;
    h.spacing = g.spacing * 2.0;
    // A coarse voxel sits at the centre of the fine voxels it averages.
    h.origin = g.toPatient(glm::dvec3(0.5));
    Volume out(h, volume.type());
    out.modality = volume.modality;
    visitVoxels(volume, [&](auto src) {
        using T = std::remove_const_t<typename decltype(src)::element_type>;
        averageBlocks<T>(src.data(), g.dims, out.voxels<T>().data(), h.dims);
    });
    return out;
}

LodPyramid::LodPyramid(const Volume& base, int smallest, int maxLevels) : base_(base) {
    const Volume* current = &base;
    while (levelCount() < maxLevels) {
        const glm::ivec3 d = current->dims();
        if (d.x <= smallest && d.y <= smallest && d.z <= smallest) {
            break;
        }
        coarser_.push_back(std::make_unique<Volume>(downsampleByTwo(*current)));
        current = coarser_.back().get();
    }
}

const Volume& LodPyramid::level(int n) const {
    if (n == 0) {
        return base_;
    }
    if (n < 0 || n >= levelCount()) {
        throw std::out_of_range("LOD level " + std::to_string(n) + " of " +
                                std::to_string(levelCount()));
    }
    return *coarser_[std::size_t(n) - 1];
}

glm::dvec3 LodPyramid::fromLevel0(const glm::dvec3& p0, int n) {
    const double f = std::ldexp(1.0, n);
    return (p0 - (f - 1.0) * 0.5) / f;
}

glm::dvec3 LodPyramid::toLevel0(const glm::dvec3& pn, int n) {
    const double f = std::ldexp(1.0, n);
    return pn * f + (f - 1.0) * 0.5;
}

} // namespace lucent
