#include "core/segmentation/SegmentSmoothing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/segmentation/SegmentEffects.h"

namespace lucent {
namespace {

constexpr int kLargestKernel = 31; // voxels per axis: a box's count fits 16 bits

// In place along one axis of the box `n` (strides 1, n.x, n.x n.y): each value becomes the
// sum over the window of `radius` voxels either side, clipped to the box.
void slidingSum(std::vector<std::uint16_t>& values, const glm::ivec3& n, int axis, int radius) {
    if (radius == 0) {
        return;
    }
    const std::size_t stride[3] = {1, std::size_t(n.x), std::size_t(n.x) * std::size_t(n.y)};
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    const int len = n[axis];
    std::vector<std::uint16_t> line(static_cast<std::size_t>(len));
    for (int p = 0; p < n[a]; ++p) {
        for (int q = 0; q < n[b]; ++q) {
            const std::size_t base = p * stride[a] + q * stride[b];
            for (int t = 0; t < len; ++t) {
                line[t] = values[base + t * stride[axis]];
            }
            unsigned sum = 0;
            for (int t = 0; t < std::min(radius, len); ++t) {
                sum += line[t];
            }
            for (int t = 0; t < len; ++t) {
                if (t + radius < len) {
                    sum += line[t + radius];
                }
                if (t - radius - 1 >= 0) {
                    sum -= line[t - radius - 1];
                }
                values[base + t * stride[axis]] = static_cast<std::uint16_t>(sum);
            }
        }
    }
}

// How many of the 2 radius + 1 positions about `at` lie within [0, size).
int inside(int at, int radius, int size) {
    return std::min(at + radius, size - 1) - std::max(at - radius, 0) + 1;
}

} // namespace

glm::ivec3 medianKernelVoxels(const VolumeGeometry& grid, double kernelMm) {
    glm::ivec3 size;
    for (int a = 0; a < 3; ++a) {
        // The odd count nearest to kernelMm / spacing, as Slicer rounds it.
        const double voxels = std::max(0.0, kernelMm) / grid.spacing[a];
        const int odd = 2 * static_cast<int>(std::lround((voxels + 1.0) / 2.0)) - 1;
        size[a] = std::clamp(odd, 1, kLargestKernel);
    }
    return size;
}

SegmentMask medianMask(const SegmentMask& mask, const VolumeGeometry& grid, double kernelMm) {
    const glm::ivec3 radius = (medianKernelVoxels(grid, kernelMm) - 1) / 2;
    if (radius == glm::ivec3(0) || !mask.any()) {
        return mask;
    }
    // Only voxels within the kernel's reach of a set voxel can be set.
    auto [lo, hi] = mask.bounds();
    lo = glm::max(lo - radius, glm::ivec3(0));
    hi = glm::min(hi + radius + 1, mask.dims());
    // Sums clipped to this box miss nothing: every set voxel lies inside it.
    const glm::ivec3 n = hi - lo;
    std::vector<std::uint16_t> counts(std::size_t(n.x) * n.y * n.z);
    for (int k = 0; k < n.z; ++k) {
        for (int j = 0; j < n.y; ++j) {
            for (int i = 0; i < n.x; ++i) {
                counts[i + std::size_t(n.x) * (j + std::size_t(n.y) * k)] =
                    mask.at(lo.x + i, lo.y + j, lo.z + k) ? 1 : 0;
            }
        }
    }
    for (int axis = 0; axis < 3; ++axis) {
        slidingSum(counts, n, axis, radius[axis]);
    }
    const glm::ivec3 dims = mask.dims();
    SegmentMask out(dims);
    for (int k = lo.z; k < hi.z; ++k) {
        const int nk = inside(k, radius.z, dims.z);
        for (int j = lo.y; j < hi.y; ++j) {
            const int njk = nk * inside(j, radius.y, dims.y);
            for (int i = lo.x; i < hi.x; ++i) {
                const int total = njk * inside(i, radius.x, dims.x);
                const std::size_t at =
                    (i - lo.x) + std::size_t(n.x) * ((j - lo.y) + std::size_t(n.y) * (k - lo.z));
                if (2 * int(counts[at]) > total) {
                    out.set(out.linearIndex(i, j, k));
                }
            }
        }
    }
    return out;
}

SegmentMask closingMask(const SegmentMask& mask, const VolumeGeometry& grid, double radiusMm) {
    if (radiusMm <= 0.0 || !mask.any()) {
        return mask;
    }
    // Padded beyond the reach of the grow, so that the shrink sees no border.
    const glm::ivec3 pad = glm::ivec3(glm::ceil(glm::dvec3(radiusMm) / grid.spacing)) + 1;
    const glm::ivec3 dims = mask.dims();
    SegmentMask padded(dims + 2 * pad);
    mask.forEachSet([&](std::size_t i) {
        const glm::ivec3 v = mask.voxelOf(i) + pad;
        padded.set(padded.linearIndex(v.x, v.y, v.z));
    });
    const SegmentMask closed = marginMask(marginMask(padded, grid, radiusMm), grid, -radiusMm);
    SegmentMask out(dims);
    closed.forEachSet([&](std::size_t i) {
        const glm::ivec3 v = closed.voxelOf(i) - pad;
        if (out.inside(v)) {
            out.set(out.linearIndex(v.x, v.y, v.z));
        }
    });
    return out;
}

} // namespace lucent
