#pragma once
// AVX2 pieces of PacketDvrKernel: eight samples per vector, each lane doing
// FastDvrKernel's float operations in FastDvrKernel's order, so that the
// packet kernel rounds as the scalar kernel does (built with
// -ffp-contract=off). Included by the packet kernel's files only.

#include <immintrin.h>

#include <cstdint>

#include <glm/glm.hpp>

#define LUCENT_AVX2 __attribute__((target("avx2,fma")))

namespace lucent::packet {

// Per lane, the voxels at[n][0] and at[n][1] as floats. Eight plain loads:
// faster than a gather instruction on the CPUs we measured (AMD Zen 4).
// The two 16-bit voxels of each 32-bit lane as floats.
LUCENT_AVX2 inline void splitPairs(__m256i g, const std::int16_t*, __m256& a, __m256& b) {
    a = _mm256_cvtepi32_ps(_mm256_srai_epi32(_mm256_slli_epi32(g, 16), 16));
    b = _mm256_cvtepi32_ps(_mm256_srai_epi32(g, 16));
}
LUCENT_AVX2 inline void splitPairs(__m256i g, const std::uint16_t*, __m256& a, __m256& b) {
    a = _mm256_cvtepi32_ps(_mm256_and_si256(g, _mm256_set1_epi32(0xffff)));
    b = _mm256_cvtepi32_ps(_mm256_srli_epi32(g, 16));
}

// Two neighbouring voxels per lane (one 32-bit load each), as two float vectors.
template <class T> LUCENT_AVX2 inline void loadPairs(const T* const at[8], __m256& a, __m256& b) {
    int v[8];
    for (int n = 0; n < 8; ++n) {
        __builtin_memcpy(&v[n], at[n], sizeof(int));
    }
    const __m256i g = _mm256_setr_epi32(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]);
    splitPairs(g, at[0], a, b);
}

LUCENT_AVX2 inline void loadPairs(const float* const at[8], __m256& a, __m256& b) {
    a = _mm256_setr_ps(at[0][0], at[1][0], at[2][0], at[3][0], at[4][0], at[5][0], at[6][0],
                       at[7][0]);
    b = _mm256_setr_ps(at[0][1], at[1][1], at[2][1], at[3][1], at[4][1], at[5][1], at[6][1],
                       at[7][1]);
}

// Lanes in `bits` as a vector mask.
LUCENT_AVX2 inline __m256 laneMask(int bits) {
    const __m256i lane = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_castsi256_ps(
        _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(bits), lane), lane));
}

// a + f * (b - a)
LUCENT_AVX2 inline __m256 lerp(__m256 a, __m256 b, __m256 f) {
    return _mm256_add_ps(a, _mm256_mul_ps(f, _mm256_sub_ps(b, a)));
}

LUCENT_AVX2 inline __m256i clampInt(__m256i v, __m256i hi) {
    return _mm256_max_epi32(_mm256_setzero_si256(), _mm256_min_epi32(v, hi));
}

LUCENT_AVX2 inline __m256i loadInts(const int* p) {
    return _mm256_load_si256(reinterpret_cast<const __m256i*>(p));
}
LUCENT_AVX2 inline void storeInts(int* p, __m256i v) {
    _mm256_store_si256(reinterpret_cast<__m256i*>(p), v);
}

LUCENT_AVX2 inline int maskBits(__m256 m) {
    return _mm256_movemask_ps(m);
}
LUCENT_AVX2 inline int maskBits(__m256i m) {
    return _mm256_movemask_ps(_mm256_castsi256_ps(m));
}

// A voxel row pair (x0, x1) per lane.
struct Pair {
    __m256 a, b;
};

// The trilinear cell of each lane: rows (y, z) for y, z in {0, 1}, as row[y + 2 z].
struct Cell {
    Pair row[4];
};

// Per lane, the voxel pair `delta` voxels on from the lane's base.
template <class T> LUCENT_AVX2 inline Pair pairAt(const T* const base[8], std::ptrdiff_t delta) {
    const T* at[8];
    for (int n = 0; n < 8; ++n) {
        at[n] = base[n] + delta;
    }
    Pair p;
    loadPairs(at, p.a, p.b);
    return p;
}

// Per lane, the four voxels at base[n] + delta + 0 .. 3 as the pairs (0, 1)
// and (2, 3): one 64-bit load per lane where a float volume needs two pairs.
template <class T>
LUCENT_AVX2 inline void rowQuads(const T* const base[8], std::ptrdiff_t delta, Pair& lo, Pair& hi) {
    if constexpr (sizeof(T) == 2) {
        long long q[8];
        for (int n = 0; n < 8; ++n) {
            __builtin_memcpy(&q[n], base[n] + delta, sizeof(long long));
        }
        // Lanes 0 1 4 5 | 2 3 6 7 after the shuffles; the permute puts them back.
        const __m256 a = _mm256_castsi256_ps(_mm256_setr_epi64x(q[0], q[1], q[2], q[3]));
        const __m256 b = _mm256_castsi256_ps(_mm256_setr_epi64x(q[4], q[5], q[6], q[7]));
        const __m256i order = _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7);
        const __m256i low = _mm256_permutevar8x32_epi32(
            _mm256_castps_si256(_mm256_shuffle_ps(a, b, _MM_SHUFFLE(2, 0, 2, 0))), order);
        const __m256i high = _mm256_permutevar8x32_epi32(
            _mm256_castps_si256(_mm256_shuffle_ps(a, b, _MM_SHUFFLE(3, 1, 3, 1))), order);
        splitPairs(low, static_cast<const T*>(nullptr), lo.a, lo.b);
        splitPairs(high, static_cast<const T*>(nullptr), hi.a, hi.b);
    } else {
        lo = pairAt(base, delta);
        hi = pairAt(base, delta + 2);
    }
}

// FastDvrKernel::gradientInside's trilinear blend of eight corner differences.
LUCENT_AVX2 inline __m256 blendCorners(const __m256 c[8], __m256 fx, __m256 fy, __m256 fz) {
    const __m256 c0 = lerp(lerp(c[0], c[1], fx), lerp(c[2], c[3], fx), fy);
    const __m256 c1 = lerp(lerp(c[4], c[5], fx), lerp(c[6], c[7], fx), fy);
    return lerp(c0, c1, fz);
}

// The four cell rows of eight lanes (row[y + 2 z] as in Cell) as voxel quads
// x - 1 .. x + 2: (x - 1, x) in lo, (x + 1, x + 2) in hi. Lanes must not lie
// on the first or last cell along x.
struct RowQuads {
    Pair lo[4], hi[4];
};

template <class T>
LUCENT_AVX2 inline void loadRowQuads(const T* const base[8], std::ptrdiff_t sy, std::ptrdiff_t sz,
                                     RowQuads& q) {
    for (int r = 0; r < 4; ++r) {
        const std::ptrdiff_t o = ((r & 1) != 0 ? sy : 0) + ((r & 2) != 0 ? sz : 0);
        rowQuads(base, o - 1, q.lo[r], q.hi[r]);
    }
}

// The cell rows (x, x + 1) within the quads.
LUCENT_AVX2 inline void cellOf(const RowQuads& q, Cell& cell) {
    for (int r = 0; r < 4; ++r) {
        cell.row[r] = Pair{q.lo[r].b, q.hi[r].a};
    }
}

// The corner differences of FastDvrKernel::gradientInside for eight lanes
// whose cells start at base[n] (all neighbours inside the volume), whose cell
// rows are `cell` and row quads `quads`: c[8 a .. 8 a + 7] along axis a,
// before the blend.
template <class T>
LUCENT_AVX2 inline void gradientCorners(const T* const base[8], const Cell& cell,
                                        const RowQuads& quads, std::ptrdiff_t sy, std::ptrdiff_t sz,
                                        __m256 c[24]) {
    // x: value(x + 1) - value(x - 1) along the four rows.
    for (int r = 0; r < 4; ++r) {
        c[2 * r] = _mm256_sub_ps(quads.hi[r].a, quads.lo[r].a);
        c[2 * r + 1] = _mm256_sub_ps(quads.hi[r].b, quads.lo[r].b);
    }
    // y: rows y - 1 and y + 2 beside the cell's rows, in both slices.
    __m256* cy = c + 8;
    for (int z = 0; z < 2; ++z) {
        const std::ptrdiff_t o = z == 0 ? 0 : sz;
        const Pair below = pairAt(base, o - sy);
        const Pair above = pairAt(base, o + 2 * sy);
        const Pair& y0 = cell.row[2 * z];
        const Pair& y1 = cell.row[2 * z + 1];
        cy[4 * z] = _mm256_sub_ps(y1.a, below.a);
        cy[4 * z + 1] = _mm256_sub_ps(y1.b, below.b);
        cy[4 * z + 2] = _mm256_sub_ps(above.a, y0.a);
        cy[4 * z + 3] = _mm256_sub_ps(above.b, y0.b);
    }
    // z: slices z - 1 and z + 2 beside the cell's slices, in both rows.
    __m256* cz = c + 16;
    for (int y = 0; y < 2; ++y) {
        const std::ptrdiff_t o = y == 0 ? 0 : sy;
        const Pair front = pairAt(base, o - sz);
        const Pair back = pairAt(base, o + 2 * sz);
        const Pair& z0 = cell.row[y];
        const Pair& z1 = cell.row[y + 2];
        cz[2 * y] = _mm256_sub_ps(z1.a, front.a);
        cz[2 * y + 1] = _mm256_sub_ps(z1.b, front.b);
        cz[4 + 2 * y] = _mm256_sub_ps(back.a, z0.a);
        cz[4 + 2 * y + 1] = _mm256_sub_ps(back.b, z0.b);
    }
}

// FastDvrKernel::gradientInside from its corner differences (gradientCorners).
LUCENT_AVX2 inline void blendGradient(const __m256 c[24], __m256 fx, __m256 fy, __m256 fz,
                                      __m256 g[3]) {
    const __m256 half = _mm256_set1_ps(0.5f);
    for (int a = 0; a < 3; ++a) {
        g[a] = _mm256_mul_ps(blendCorners(c + 8 * a, fx, fy, fz), half);
    }
}

// Eight rgba rows (one per lane) as four vectors r, g, b, a.
LUCENT_AVX2 inline void transpose(const glm::vec4 rows[8], __m256 out[4]) {
    auto row = [&](int n) { return _mm_loadu_ps(&rows[n].x); };
    const __m256 m0 = _mm256_set_m128(row(4), row(0)), m1 = _mm256_set_m128(row(5), row(1));
    const __m256 m2 = _mm256_set_m128(row(6), row(2)), m3 = _mm256_set_m128(row(7), row(3));
    const __m256 t0 = _mm256_unpacklo_ps(m0, m1), t1 = _mm256_unpackhi_ps(m0, m1);
    const __m256 t2 = _mm256_unpacklo_ps(m2, m3), t3 = _mm256_unpackhi_ps(m2, m3);
    out[0] = _mm256_shuffle_ps(t0, t2, 0x44);
    out[1] = _mm256_shuffle_ps(t0, t2, 0xee);
    out[2] = _mm256_shuffle_ps(t1, t3, 0x44);
    out[3] = _mm256_shuffle_ps(t1, t3, 0xee);
}

// glm's m * v for the columns of a mat3 (sums left to right).
LUCENT_AVX2 inline void multiply(const glm::mat3& m, const __m256 v[3], __m256 out[3]) {
    for (int r = 0; r < 3; ++r) {
        const __m256 s0 = _mm256_mul_ps(_mm256_set1_ps(m[0][r]), v[0]);
        const __m256 s1 = _mm256_mul_ps(_mm256_set1_ps(m[1][r]), v[1]);
        const __m256 s2 = _mm256_mul_ps(_mm256_set1_ps(m[2][r]), v[2]);
        out[r] = _mm256_add_ps(_mm256_add_ps(s0, s1), s2);
    }
}

// glm::dot (products summed left to right).
LUCENT_AVX2 inline __m256 dot(const __m256 a[3], const __m256 b[3]) {
    return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a[0], b[0]), _mm256_mul_ps(a[1], b[1])),
                         _mm256_mul_ps(a[2], b[2]));
}

// integerPower for eight lanes.
LUCENT_AVX2 inline __m256 integerPower(__m256 x, unsigned n) {
    __m256 r = _mm256_set1_ps(1.0f);
    while (n != 0u) {
        if ((n & 1u) != 0u) {
            r = _mm256_mul_ps(r, x);
        }
        x = _mm256_mul_ps(x, x);
        n >>= 1u;
    }
    return r;
}

} // namespace lucent::packet
