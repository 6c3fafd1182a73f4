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

// GCC builds an AVX2 clone of the loop below and picks one at load time; clang
// (the fuzz build, LUCENT_FUZZ) cannot clone a template and gets the portable loop.
#if defined(__clang__)
#define LUCENT_AVX2_CLONE
#else
#define LUCENT_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#endif

// classify(v) of each voxel of a slice.
template <class T>
LUCENT_AVX2_CLONE void classifySlice(const Classify<T>& classify, const T* __restrict v,
                                     std::size_t n, std::uint8_t* __restrict out) {
    for (std::size_t i = 0; i < n; ++i) {
        out[i] = classify(v[i]);
    }
}

// One bit per cell, row by row: bit i % 64 of word (j + ny k) rowWords + i / 64.
struct CellBits {
    glm::ivec3 n{0};
    int rowWords = 0;
    std::vector<std::uint64_t> words;

    explicit CellBits(glm::ivec3 dims)
        : n(dims), rowWords((dims.x + 63) / 64),
          words(std::size_t((dims.x + 63) / 64) * std::size_t(dims.y) * std::size_t(dims.z), 0) {}
    std::uint64_t* row(int j, int k) {
        return words.data() + (std::size_t(j) + std::size_t(n.y) * std::size_t(k)) * rowWords;
    }
    const std::uint64_t* row(int j, int k) const { return const_cast<CellBits*>(this)->row(j, k); }
};

template <class T> void findCells(const T* data, double lo, double hi, CellBits& out) {
    const Classify<T> classify(lo, hi);
    const glm::ivec3 n = out.n;
    const std::size_t sy = std::size_t(n.x), sz = sy * std::size_t(n.y);
#pragma omp parallel
    {
        // The classes of slices k and k + 1 (each slice classified once per
        // thread), what the two share along z, then per x what the four voxels
        // of the column (y, z) .. (y + 1, z + 1) share.
        std::vector<std::uint8_t> here(sz), next(sz), pair(sz), column(sy);
        std::vector<std::uint8_t> cell(std::size_t(out.rowWords) * 64, 0);
        int classified = -1; // the slice in `next`
#pragma omp for schedule(static)
        for (int k = 0; k < n.z - 2; ++k) {
            if (classified == k) {
                here.swap(next);
            } else {
                classifySlice(classify, data + std::size_t(k) * sz, sz, here.data());
            }
            classifySlice(classify, data + std::size_t(k + 1) * sz, sz, next.data());
            classified = k + 1;
            {
                const std::uint8_t* __restrict a = here.data();
                const std::uint8_t* __restrict b = next.data();
                std::uint8_t* __restrict p = pair.data();
                for (std::size_t i = 0; i < sz; ++i) {
                    p[i] = a[i] & b[i];
                }
            }
            for (int j = 0; j < n.y - 2; ++j) {
                const std::uint8_t* __restrict a = pair.data() + std::size_t(j) * sy;
                const std::uint8_t* __restrict b = a + sy;
                std::uint8_t* __restrict c = column.data();
                for (int i = 0; i < n.x; ++i) {
                    c[i] = a[i] & b[i];
                }
                std::uint8_t* __restrict cells = cell.data();
                for (int i = 0; i + 2 < n.x; ++i) {
                    cells[i] = (c[i] & c[i + 1]) != 0 ? 1 : 0;
                }
                // Eight 0/1 bytes to eight bits, lowest byte to lowest bit.
                auto* bytes = reinterpret_cast<std::uint8_t*>(out.row(j, k));
                for (int byte = 0; byte < out.rowWords * 8; ++byte) {
                    std::uint64_t eight;
                    std::memcpy(&eight, &cells[std::size_t(byte) * 8], 8);
                    bytes[byte] = std::uint8_t((eight * 0x0102040810204080ull) >> 56);
                }
            }
        }
    }
}

// The cells whose 3 x 3 x 3 neighbourhood lies in `in` (cells beyond the
// volume are not in it).
CellBits erode(const CellBits& in) {
    const glm::ivec3 n = in.n;
    const int words = in.rowWords;
    CellBits alongX(n), out(n);
#pragma omp parallel for schedule(static)
    for (int k = 0; k < n.z; ++k) {
        for (int j = 0; j < n.y; ++j) {
            const std::uint64_t* a = in.row(j, k);
            std::uint64_t* o = alongX.row(j, k);
            for (int w = 0; w < words; ++w) {
                const std::uint64_t below = a[w] << 1 | (w > 0 ? a[w - 1] >> 63 : 0);
                const std::uint64_t above = a[w] >> 1 | (w + 1 < words ? a[w + 1] << 63 : 0);
                o[w] = a[w] & below & above;
            }
        }
    }
#pragma omp parallel for schedule(static)
    for (int k = 1; k < n.z - 1; ++k) {
        for (int j = 1; j < n.y - 1; ++j) {
            std::uint64_t* o = out.row(j, k);
            for (int w = 0; w < words; ++w) {
                std::uint64_t m = ~0ull;
                for (int dz = -1; dz <= 1; ++dz) {
                    for (int dy = -1; dy <= 1; ++dy) {
                        m &= alongX.row(j + dy, k + dz)[w];
                    }
                }
                o[w] = m;
            }
        }
    }
    return out;
}

// Bits 0 .. 7 of x at bits 0, 2 .. 14.
std::uint32_t spread(std::uint32_t x) {
    x = (x | x << 4) & 0x0f0fu;
    x = (x | x << 2) & 0x3333u;
    return (x | x << 1) & 0x5555u;
}

} // namespace

InvisibleCells findInvisibleCells(const Volume& volume, double lo, double hi) {
    const glm::ivec3 n = volume.geometry().dims;
    InvisibleCells out;
    out.blocks = (n + 7) / 8;
    out.words.assign(std::size_t(out.blocks.x) * out.blocks.y * out.blocks.z * 32, 0u);
    if (n.x < 3 || n.y < 3 || n.z < 3) {
        return out;
    }
    CellBits invisible(n);
    visitVoxels(volume, [&](auto v) { findCells(v.data(), lo, hi, invisible); });
    const CellBits one = erode(invisible), two = erode(one);
    // Clearance 1 + (in one) + (in two), the sets nested; eight cells along x
    // make the 16 bits of their row in a block.
    auto* halves = reinterpret_cast<std::uint16_t*>(out.words.data());
#pragma omp parallel for schedule(static)
    for (int k = 0; k < n.z; ++k) {
        for (int j = 0; j < n.y; ++j) {
            const auto* c0 = reinterpret_cast<const std::uint8_t*>(invisible.row(j, k));
            const auto* c1 = reinterpret_cast<const std::uint8_t*>(one.row(j, k));
            const auto* c2 = reinterpret_cast<const std::uint8_t*>(two.row(j, k));
            const std::size_t first = InvisibleCells::wordOf({0, j, k}, out.blocks) * 2 + (j & 1);
            for (int b = 0; b < out.blocks.x; ++b) {
                const std::uint32_t low = (c0[b] & ~c1[b]) | c2[b], high = c1[b];
                halves[first + std::size_t(b) * 64] =
                    std::uint16_t(spread(low) | spread(high) << 1);
            }
        }
    }
    return out;
}

} // namespace lucent
