#include "core/volume/BrickResidency.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace lucent {

namespace {

int mirrorIndex(int i, int n) {
    if (n == 1) {
        return 0;
    }
    const int period = 2 * (n - 1);
    i = ((i % period) + period) % period;
    return i < n ? i : period - i;
}

int clamped(int i, int n) {
    return std::clamp(i, 0, n - 1);
}

const auto rowOf = [](const auto* data, glm::ivec3 dims, int j, int k) {
    return data + std::size_t(dims.x) * (std::size_t(j) + std::size_t(dims.y) * std::size_t(k));
};

// Visits the central differences of every voxel of the box, a row at a time:
// f(a, b, c, dx, dy, dz) with (a, b, c) the box-local voxel.
template <class T, class F>
void forEachDifference(const T* data, glm::ivec3 dims, glm::ivec3 lo, glm::ivec3 size, F&& f) {
    // Every index clamped to the volume, the neighbours' too, worked out once
    // per axis: the inner loop reads rows without a clamp.
    const std::size_t n = std::size_t(size.x);
    std::vector<int> xs(n, 0), xm(n, 0), xp(n, 0);
    for (int a = 0; a < size.x; ++a) {
        const int i = clamped(lo.x + a, dims.x);
        xs[std::size_t(a)] = i;
        xm[std::size_t(a)] = clamped(i - 1, dims.x);
        xp[std::size_t(a)] = clamped(i + 1, dims.x);
    }
    for (int c = 0; c < size.z; ++c) {
        const int k = clamped(lo.z + c, dims.z);
        for (int b = 0; b < size.y; ++b) {
            const int j = clamped(lo.y + b, dims.y);
            const T* here = rowOf(data, dims, j, k);
            const T* jm = rowOf(data, dims, clamped(j - 1, dims.y), k);
            const T* jp = rowOf(data, dims, clamped(j + 1, dims.y), k);
            const T* km = rowOf(data, dims, j, clamped(k - 1, dims.z));
            const T* kp = rowOf(data, dims, j, clamped(k + 1, dims.z));
            for (std::size_t a = 0; a < n; ++a) {
                const int i = xs[a];
                f(a, b, c, 0.5 * (double(here[xp[a]]) - double(here[xm[a]])),
                  0.5 * (double(jp[i]) - double(jm[i])), 0.5 * (double(kp[i]) - double(km[i])));
            }
        }
    }
}

} // namespace

template <class T>
void extractBox(const T* data, glm::ivec3 dims, glm::ivec3 lo, glm::ivec3 size, BrickEdge edge,
                T* out) {
    const auto index = [&](int i, int n) {
        return edge == BrickEdge::Clamp ? clamped(i, n) : mirrorIndex(i, n);
    };
    std::vector<int> xs(std::size_t(size.x), 0);
    for (int a = 0; a < size.x; ++a) {
        xs[std::size_t(a)] = index(lo.x + a, dims.x);
    }
    const bool inside = lo.x >= 0 && lo.x + size.x <= dims.x;
    for (int c = 0; c < size.z; ++c) {
        const int k = index(lo.z + c, dims.z);
        for (int b = 0; b < size.y; ++b) {
            const T* row = rowOf(data, dims, index(lo.y + b, dims.y), k);
            T* dst = out + std::size_t(size.x) * (std::size_t(b) + std::size_t(size.y) * c);
            if (inside) {
                std::copy(row + lo.x, row + lo.x + size.x, dst);
            } else {
                for (int a = 0; a < size.x; ++a) {
                    dst[a] = row[xs[std::size_t(a)]];
                }
            }
        }
    }
}

template <class T>
void extractGradientBox(const T* data, glm::ivec3 dims, glm::ivec3 lo, glm::ivec3 size, double unit,
                        std::int16_t* out) {
    const double inverse = 1.0 / unit;
    const auto quantised = [&](double d) {
        return std::int16_t(std::clamp(std::lround(d * inverse), -32767L, 32767L));
    };
    forEachDifference(
        data, dims, lo, size, [&](std::size_t a, int b, int c, double x, double y, double z) {
            std::int16_t* dst =
                out + 4 * (a + std::size_t(size.x) * (std::size_t(b) + std::size_t(size.y) * c));
            dst[0] = quantised(x);
            dst[1] = quantised(y);
            dst[2] = quantised(z);
            dst[3] = 0;
        });
}

#define LUCENT_EXTRACT(T)                                                                          \
    template void extractBox<T>(const T*, glm::ivec3, glm::ivec3, glm::ivec3, BrickEdge, T*);      \
    template void extractGradientBox<T>(const T*, glm::ivec3, glm::ivec3, glm::ivec3, double,      \
                                        std::int16_t*);
LUCENT_EXTRACT(std::int16_t)
LUCENT_EXTRACT(std::uint16_t)
LUCENT_EXTRACT(float)
#undef LUCENT_EXTRACT

} // namespace lucent
