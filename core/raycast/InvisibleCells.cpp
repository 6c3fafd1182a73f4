#include "core/raycast/InvisibleCells.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

namespace lucent {

static_assert(std::endian::native == std::endian::little, "cell bits are packed bytewise");

namespace {

// 1 where a voxel lies below lo, 2 where above hi, 0 where neither. Integer
// voxels compare with integer bounds (v < lo <=> v < ceil(lo)), in their own
// type where the bounds fit it, so that the loops stay narrow vectors.
template <class T> struct Classify {
    T below{}, above{};
    std::uint8_t allBelow = 0, allAbove = 0; // bounds beyond the type's range

    Classify(double lo, double hi) {
        if constexpr (std::is_integral_v<T>) {
            const double min = std::numeric_limits<T>::min(), max = std::numeric_limits<T>::max();
            const double b = std::ceil(lo), a = std::floor(hi);
            allBelow = b > max ? 1 : 0;
            allAbove = a < min ? 2 : 0;
            below = T(std::clamp(b, min, max)); // b <= min: v < min never holds
            above = T(std::clamp(a, min, max)); // a >= max: v > max never holds
        } else {
            below = T(lo); // float voxels: lo and hi round outwards below
            above = T(hi);
            if (double(below) > lo) {
                below = std::nextafter(below, -std::numeric_limits<T>::infinity());
            }
            if (double(above) < hi) {
                above = std::nextafter(above, std::numeric_limits<T>::infinity());
            }
        }
    }
    std::uint8_t operator()(T v) const {
        return std::uint8_t(((v < below ? 1 : 0) | allBelow) | ((v > above ? 2 : 0) | allAbove));
    }
};

// What the voxels of rows a and b share, per x.
template <class T>
void shared(const Classify<T>& classify, const T* __restrict a, const T* __restrict b, int n,
            std::uint8_t* __restrict out) {
    for (int i = 0; i < n; ++i) {
        out[i] = classify(a[i]) & classify(b[i]);
    }
}

template <class T>
void findCells(const T* data, glm::ivec3 n, double lo, double hi, InvisibleCells& out) {
    const Classify<T> classify(lo, hi);
    const std::size_t sy = std::size_t(n.x), sz = sy * std::size_t(n.y);
#pragma omp parallel
    {
        // Per x, what the two voxels along z share in row j and in row j + 1,
        // then what the four of the column (y, z) .. (y + 1, z + 1) share.
        std::vector<std::uint8_t> rowJ(sy), rowNext(sy), column(sy);
        std::vector<std::uint8_t> cell(std::size_t(out.blocks.x) * 8, 0);
#pragma omp for schedule(static)
        for (int k = 0; k < n.z - 2; ++k) {
            const T* slice = data + std::size_t(k) * sz;
            shared(classify, slice, slice + sz, n.x, rowJ.data());
            for (int j = 0; j < n.y - 2; ++j) {
                const T* next = slice + std::size_t(j + 1) * sy;
                shared(classify, next, next + sz, n.x, rowNext.data());
                const std::uint8_t* __restrict a = rowJ.data();
                const std::uint8_t* __restrict b = rowNext.data();
                std::uint8_t* __restrict c = column.data();
                for (int i = 0; i < n.x; ++i) {
                    c[i] = a[i] & b[i];
                }
                std::uint8_t* __restrict cells = cell.data();
                for (int i = 0; i + 2 < n.x; ++i) {
                    cells[i] = (c[i] & c[i + 1]) != 0 ? 1 : 0;
                }
                // Eight 0/1 bytes to eight bits, lowest byte to lowest bit:
                // the byte of row (j, k) in each block along x.
                auto* bytes = reinterpret_cast<std::uint8_t*>(out.words.data());
                const std::size_t first =
                    InvisibleCells::wordOf({0, j, k}, out.blocks) * 4 + std::size_t(j & 3);
                for (int b = 0; b < out.blocks.x; ++b) {
                    std::uint64_t eight;
                    std::memcpy(&eight, &cells[std::size_t(b) * 8], 8);
                    bytes[first + std::size_t(b) * 64] =
                        std::uint8_t((eight * 0x0102040810204080ull) >> 56);
                }
                rowJ.swap(rowNext);
            }
        }
    }
}

} // namespace

InvisibleCells findInvisibleCells(const Volume& volume, double lo, double hi) {
    const glm::ivec3 n = volume.geometry().dims;
    InvisibleCells out;
    out.blocks = (n + 7) / 8;
    out.words.assign(std::size_t(out.blocks.x) * out.blocks.y * out.blocks.z * 16, 0u);
    if (n.x >= 3 && n.y >= 3 && n.z >= 3) {
        visitVoxels(volume, [&](auto v) { findCells(v.data(), n, lo, hi, out); });
    }
    return out;
}

} // namespace lucent
