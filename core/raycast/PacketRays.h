#pragma once
// The rays of a PacketDvrKernel packet in double: where each ray enters and
// leaves the volume (raySpan), its lattice, and where it leaves a box of
// leapable cells (FastDvrKernel::boxExit), four lanes per vector with the
// same double operations per lane as the scalar code. Included by
// PacketDvrKernel.cpp and its tests only, built with -ffp-contract=off (a
// fused multiply-add would round otherwise than the scalar code).

#include <cmath>
#include <limits>

#include "core/raycast/PacketMath.h"
#include "core/raycast/RaySetup.h"

namespace lucent::packet {

// Lanes 0-3 (h = 0) or 4-7 (h = 1) of v.
LUCENT_AVX2 inline __m128i halfOf(int h, __m256i v) {
    return h == 0 ? _mm256_castsi256_si128(v) : _mm256_extracti128_si256(v, 1);
}

// std::min and std::max per lane: (b < a ? b : a) and (a < b ? b : a).
LUCENT_AVX2 inline __m256d minOf(__m256d a, __m256d b) {
    return _mm256_blendv_pd(a, b, _mm256_cmp_pd(b, a, _CMP_LT_OQ));
}
LUCENT_AVX2 inline __m256d maxOf(__m256d a, __m256d b) {
    return _mm256_blendv_pd(a, b, _mm256_cmp_pd(a, b, _CMP_LT_OQ));
}

// The eight rays' lattices in double, per axis: FastDvrKernel::Lattice.
struct LeapLattice {
    alignas(32) double entry[3][8]{}, stride[3][8]{}, inverse[3][8]{};
};

// Eight rays as FastDvrKernel::cast starts them: lattice p(n) = entry +
// stride * n in float and in double, samples first .. last, unit direction.
struct PacketRays {
    alignas(32) float entry[3][8]{}, stride[3][8]{}, dir[3][8]{};
    alignas(32) int first[8]{}, last[8]{};
    LeapLattice lattice;
    int active = 0; // the lanes whose ray takes a sample
};

// raySpan and the lattice of rays 0 .. count - 1 (count <= 8) from o along
// d[r] (index space) with unit directions w[r].
LUCENT_AVX2 inline void startRays(const RaySetup<float>& s, const glm::dvec3& o,
                                  const glm::dvec3* d, const glm::dvec3* w, int count,
                                  PacketRays& rays) {
    alignas(32) double dir[3][8]{};
    for (int r = 0; r < count; ++r) {
        for (int a = 0; a < 3; ++a) {
            dir[a][r] = d[r][a];
            rays.dir[a][r] = float(w[r][a]);
        }
    }
    const __m256d inf = _mm256_set1_pd(std::numeric_limits<double>::infinity());
    const __m256d minusInf = _mm256_set1_pd(-std::numeric_limits<double>::infinity());
    const __m256d absMask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffll));
    const __m256d tiny = _mm256_set1_pd(1e-15), dt = _mm256_set1_pd(s.dt);
    rays.active = 0;
    for (int h = 0; h < 2; ++h) {
        __m256d t0 = minusInf, t1 = inf, c0 = minusInf, c1 = inf;
        __m256d miss = _mm256_setzero_pd();
        __m256d da[3];
        for (int a = 0; a < 3; ++a) {
            da[a] = _mm256_load_pd(&dir[a][4 * h]);
            // Along an axis the ray does not cross, it misses unless o lies
            // within the box and the clip box; the axis bounds nothing else.
            const __m256d flat = _mm256_cmp_pd(_mm256_and_pd(da[a], absMask), tiny, _CMP_LT_OQ);
            if (o[a] < s.boxLo[a] || o[a] > s.boxHi[a] || o[a] < s.clipLo[a] ||
                o[a] > s.clipHi[a]) {
                miss = _mm256_or_pd(miss, flat);
            }
            const __m256d oa = _mm256_set1_pd(o[a]);
            const __m256d ta = _mm256_div_pd(_mm256_sub_pd(_mm256_set1_pd(s.boxLo[a]), oa), da[a]);
            const __m256d tb = _mm256_div_pd(_mm256_sub_pd(_mm256_set1_pd(s.boxHi[a]), oa), da[a]);
            t0 = maxOf(t0, _mm256_blendv_pd(minOf(ta, tb), minusInf, flat));
            t1 = minOf(t1, _mm256_blendv_pd(maxOf(ta, tb), inf, flat));
            const bool unclipped = s.clipLo[a] == s.boxLo[a] && s.clipHi[a] == s.boxHi[a];
            const __m256d ca =
                unclipped ? ta
                          : _mm256_div_pd(_mm256_sub_pd(_mm256_set1_pd(s.clipLo[a]), oa), da[a]);
            const __m256d cb =
                unclipped ? tb
                          : _mm256_div_pd(_mm256_sub_pd(_mm256_set1_pd(s.clipHi[a]), oa), da[a]);
            c0 = maxOf(c0, _mm256_blendv_pd(minOf(ca, cb), minusInf, flat));
            c1 = minOf(c1, _mm256_blendv_pd(maxOf(ca, cb), inf, flat));
        }
        t0 = maxOf(t0, _mm256_setzero_pd());
        const __m256d tEnd = minOf(t1, c1);
        miss = _mm256_or_pd(miss, _mm256_or_pd(_mm256_cmp_pd(t1, t0, _CMP_LT_OQ),
                                               _mm256_cmp_pd(tEnd, maxOf(t0, c0), _CMP_LT_OQ)));
        const __m256d big = _mm256_set1_pd(2e9), eps = _mm256_set1_pd(1e-9);
        const __m256d first = _mm256_blendv_pd(
            _mm256_setzero_pd(),
            _mm256_ceil_pd(_mm256_sub_pd(_mm256_div_pd(_mm256_sub_pd(c0, t0), dt), eps)),
            _mm256_cmp_pd(c0, t0, _CMP_GT_OQ));
        const __m256d last =
            _mm256_floor_pd(_mm256_add_pd(_mm256_div_pd(_mm256_sub_pd(tEnd, t0), dt), eps));
        const __m128i firstN = _mm256_cvttpd_epi32(_mm256_min_pd(first, big));
        const __m128i lastN = _mm256_cvttpd_epi32(_mm256_max_pd(_mm256_min_pd(last, big), -big));
        _mm_store_si128(reinterpret_cast<__m128i*>(&rays.first[4 * h]), firstN);
        _mm_store_si128(reinterpret_cast<__m128i*>(&rays.last[4 * h]), lastN);
        const int empty = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(firstN, lastN)));
        const int counted = count >= 4 * h + 4 ? 15
                            : count > 4 * h    ? (1 << (count - 4 * h)) - 1
                                               : 0;
        rays.active |= (counted & ~_mm256_movemask_pd(miss) & ~empty) << (4 * h);
        for (int a = 0; a < 3; ++a) {
            // p(n) = (o + d t0) + (d dt) n, as glm computes it per component.
            const __m256d entry = _mm256_add_pd(_mm256_set1_pd(o[a]), _mm256_mul_pd(da[a], t0));
            const __m256d stride = _mm256_mul_pd(da[a], dt);
            _mm256_store_pd(&rays.lattice.entry[a][4 * h], entry);
            _mm256_store_pd(&rays.lattice.stride[a][4 * h], stride);
            _mm256_store_pd(
                &rays.lattice.inverse[a][4 * h],
                _mm256_and_pd(_mm256_div_pd(_mm256_set1_pd(1.0), stride),
                              _mm256_cmp_pd(_mm256_and_pd(stride, absMask), tiny, _CMP_GT_OQ)));
            _mm_store_ps(&rays.entry[a][4 * h], _mm256_cvtpd_ps(entry));
            _mm_store_ps(&rays.stride[a][4 * h], _mm256_cvtpd_ps(stride));
        }
    }
    // A part of a volume (RaySetup::part) has open faces: its spans come from
    // the scalar raySpan, which knows them (the same t0, so the same lattice).
    if (s.part) {
        for (int r = 0; r < count; ++r) {
            RaySpan span;
            const bool hit = raySpan(s, o, d[r], span) && span.nFirst <= span.nLast;
            rays.first[r] = hit ? int(span.nFirst) : 0;
            rays.last[r] = hit ? int(span.nLast) : -1;
            rays.active = hit ? (rays.active | (1 << r)) : (rays.active & ~(1 << r));
        }
    }
}

// FastDvrKernel::boxExit for eight lanes, cells lo .. hi of a level of cells
// of `size` voxels, perAxis of them: the same double operations per lane.
// Lanes 0-3 in exit[0], 4-7 in exit[1].
LUCENT_AVX2 inline void boxExits(const __m256i lo[3], const __m256i hi[3], int size,
                                 glm::ivec3 perAxis, const LeapLattice& l, __m256d exit[2]) {
    exit[0] = exit[1] = _mm256_set1_pd(std::numeric_limits<double>::infinity());
    const __m256i one = _mm256_set1_epi32(1), vSize = _mm256_set1_epi32(size);
    for (int a = 0; a < 3; ++a) {
        const __m256i up = _mm256_mullo_epi32(_mm256_add_epi32(hi[a], one), vSize);
        const __m256i down = _mm256_mullo_epi32(lo[a], vSize);
        const __m256i upOk = _mm256_cmpgt_epi32(_mm256_set1_epi32(perAxis[a] - 1), hi[a]);
        const __m256i downOk = _mm256_cmpgt_epi32(lo[a], _mm256_setzero_si256());
        for (int h = 0; h < 2; ++h) {
            const __m256d st = _mm256_load_pd(&l.stride[a][4 * h]);
            const __m256d pos = _mm256_cmp_pd(st, _mm256_set1_pd(1e-15), _CMP_GT_OQ);
            const __m256d neg = _mm256_cmp_pd(st, _mm256_set1_pd(-1e-15), _CMP_LT_OQ);
            const __m256d valid = _mm256_or_pd(
                _mm256_and_pd(pos, _mm256_castsi256_pd(_mm256_cvtepi32_epi64(halfOf(h, upOk)))),
                _mm256_and_pd(neg, _mm256_castsi256_pd(_mm256_cvtepi32_epi64(halfOf(h, downOk)))));
            const __m256d bound = _mm256_blendv_pd(_mm256_cvtepi32_pd(halfOf(h, down)),
                                                   _mm256_cvtepi32_pd(halfOf(h, up)), pos);
            const __m256d t =
                _mm256_mul_pd(_mm256_sub_pd(bound, _mm256_load_pd(&l.entry[a][4 * h])),
                              _mm256_load_pd(&l.inverse[a][4 * h]));
            exit[h] = _mm256_blendv_pd(exit[h], _mm256_min_pd(t, exit[h]), valid);
        }
    }
}

} // namespace lucent::packet
