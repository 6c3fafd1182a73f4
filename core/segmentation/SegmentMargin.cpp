// Margin grow and shrink through an exact Euclidean distance transform: Felzenszwalb and
// Huttenlocher's lower envelope of parabolas ("Distance Transforms of Sampled Functions",
// Theory of Computing 8, 2012), one pass per axis with that axis's spacing, inside the
// mask's bounding box widened by the margin (the nearest voxel that matters lies there).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/segmentation/SegmentEffects.h"

namespace lucent {
namespace {

constexpr double kFar = std::numeric_limits<double>::infinity();

// One line of n samples f (squared distances so far), spaced `s` mm: in place, the
// squared distance to the nearest sample p, min over p of (s (q - p))^2 + f(p).
void envelope(std::vector<double>& f, int n, double s, std::vector<int>& v, std::vector<double>& z,
              std::vector<double>& out) {
    // Where the parabolas of samples p and q (q > p) cross, in mm along the line.
    const auto cross = [&](int p, int q) {
        const double xp = s * p, xq = s * q;
        return ((f[q] + xq * xq) - (f[p] + xp * xp)) / (2.0 * (xq - xp));
    };
    int k = -1;
    for (int q = 0; q < n; ++q) {
        if (f[q] == kFar) {
            continue; // no parabola: nothing set here yet
        }
        double at = -kFar;
        while (k >= 0) {
            at = cross(v[k], q);
            if (at > z[k]) {
                break;
            }
            --k;
            at = -kFar;
        }
        ++k;
        v[k] = q;
        z[k] = at;
        z[k + 1] = kFar;
    }
    if (k < 0) {
        return; // nothing on this line
    }
    int j = 0;
    for (int q = 0; q < n; ++q) {
        const double xq = s * q;
        while (z[j + 1] < xq) {
            ++j;
        }
        const double d = xq - s * v[j];
        out[q] = d * d + f[v[j]];
    }
    std::copy_n(out.begin(), n, f.begin());
}

// Squared distance (mm^2) from each voxel of the box [lo, hi) to the nearest voxel where
// `seed` holds, over the box only.
std::vector<double> squaredDistances(const glm::ivec3& lo, const glm::ivec3& hi,
                                     const glm::dvec3& spacing, auto seed) {
    const glm::ivec3 n = hi - lo;
    const std::size_t nx = n.x, nxy = nx * n.y;
    std::vector<double> d(nxy * n.z, kFar);
    for (int k = 0; k < n.z; ++k) {
        for (int j = 0; j < n.y; ++j) {
            for (int i = 0; i < n.x; ++i) {
                if (seed(lo.x + i, lo.y + j, lo.z + k)) {
                    d[i + nx * j + nxy * k] = 0.0;
                }
            }
        }
    }
    const int longest = std::max({n.x, n.y, n.z});
    std::vector<double> line(longest), out(longest), z(longest + 1);
    std::vector<int> v(longest);
    const std::array<std::size_t, 3> stride{1, nx, nxy};
    for (int axis = 0; axis < 3; ++axis) {
        const int len = n[axis];
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        for (int p = 0; p < n[a]; ++p) {
            for (int q = 0; q < n[b]; ++q) {
                const std::size_t base = p * stride[a] + q * stride[b];
                for (int t = 0; t < len; ++t) {
                    line[t] = d[base + t * stride[axis]];
                }
                envelope(line, len, spacing[axis], v, z, out);
                for (int t = 0; t < len; ++t) {
                    d[base + t * stride[axis]] = line[t];
                }
            }
        }
    }
    return d;
}

} // namespace

SegmentMask marginMask(const SegmentMask& mask, const VolumeGeometry& grid, double mm) {
    if (mm == 0.0 || !mask.any()) {
        return mask;
    }
    auto [lo, hi] = mask.bounds();
    const double r2 = mm * mm * (1.0 + 1e-9);
    SegmentMask out(mask.dims());
    if (mm > 0.0) {
        const glm::ivec3 reach(glm::ceil(glm::dvec3(mm) / grid.spacing));
        lo = glm::max(lo - reach, glm::ivec3(0));
        hi = glm::min(hi + reach + 1, mask.dims());
        const std::vector<double> d = squaredDistances(
            lo, hi, grid.spacing, [&](int i, int j, int k) { return mask.at(i, j, k); });
        const glm::ivec3 n = hi - lo;
        for (std::size_t at = 0; at < d.size(); ++at) {
            if (d[at] <= r2) {
                const int i = static_cast<int>(at % n.x), j = static_cast<int>(at / n.x % n.y),
                          k = static_cast<int>(at / (std::size_t(n.x) * n.y));
                out.set(out.linearIndex(lo.x + i, lo.y + j, lo.z + k));
            }
        }
        return out;
    }
    // Shrink: distances to the unset voxels, one layer beyond the box (outside the grid too).
    lo -= 1;
    hi += 2;
    const std::vector<double> d = squaredDistances(lo, hi, grid.spacing, [&](int i, int j, int k) {
        return !mask.inside({i, j, k}) || !mask.at(i, j, k);
    });
    const glm::ivec3 n = hi - lo;
    mask.forEachSet([&](std::size_t at) {
        const glm::ivec3 v = mask.voxelOf(at) - lo;
        if (d[v.x + std::size_t(n.x) * (v.y + std::size_t(n.y) * v.z)] > r2) {
            out.set(at);
        }
    });
    return out;
}

} // namespace lucent
