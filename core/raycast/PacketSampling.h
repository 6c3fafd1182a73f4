#pragma once
// What the packet kernel does at a sample, eight lanes at a time: the
// clearance of its cell (InvisibleCells), the table's colour and opacity, the
// headlight shading. Included by PacketDvrKernel.cpp only, built with
// -ffp-contract=off.

#include <bit>
#include <cmath>

#include "core/raycast/InvisibleCells.h"
#include "core/raycast/PacketMath.h"

namespace lucent::packet {

// Per lane in `lanes`, InvisibleCells::clearance of its cell (i, j, k); 0 in
// the other lanes.
struct CellClearance {
    const int* words = nullptr;
    glm::ivec3 blocks{0};
    explicit CellClearance(const InvisibleCells* cells) {
        if (cells != nullptr) {
            words = reinterpret_cast<const int*>(cells->words.data());
            blocks = cells->blocks;
        }
    }
    // InvisibleCells::wordOf and shiftOf for eight lanes.
    LUCENT_AVX2 __m256i operator()(__m256i i, __m256i j, __m256i k, int lanes) const {
        const __m256i one = _mm256_set1_epi32(1), seven = _mm256_set1_epi32(7);
        const __m256i row = _mm256_add_epi32(
            _mm256_srli_epi32(j, 3),
            _mm256_mullo_epi32(_mm256_set1_epi32(blocks.y), _mm256_srli_epi32(k, 3)));
        const __m256i block = _mm256_add_epi32(
            _mm256_srli_epi32(i, 3), _mm256_mullo_epi32(_mm256_set1_epi32(blocks.x), row));
        const __m256i inBlock =
            _mm256_srli_epi32(_mm256_add_epi32(_mm256_and_si256(j, seven),
                                               _mm256_slli_epi32(_mm256_and_si256(k, seven), 3)),
                              1);
        const __m256i word = _mm256_add_epi32(_mm256_slli_epi32(block, 5), inBlock);
        const __m256i shift = _mm256_add_epi32(_mm256_slli_epi32(_mm256_and_si256(i, seven), 1),
                                               _mm256_slli_epi32(_mm256_and_si256(j, one), 4));
        const __m256i bits = _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), words, word,
                                                         _mm256_castps_si256(laneMask(lanes)), 4);
        return _mm256_and_si256(_mm256_srlv_epi32(bits, shift), _mm256_set1_epi32(3));
    }
};

// FastDvrKernel's clearanceSkip for eight lanes at positions q in cells
// `cell` of clearance c (0 where c is 0); inverse[a][lane] = 1 / |stride|.
LUCENT_AVX2 inline __m256i clearanceSkips(const __m256 q[3], const __m256i cell[3], __m256i c,
                                          const __m256 stride[3], const float inverse[3][8]) {
    const __m256i r = _mm256_sub_epi32(c, _mm256_set1_epi32(1)), one = _mm256_set1_epi32(1);
    const __m256 spare = _mm256_set1_ps(0.01f), zero = _mm256_setzero_ps();
    __m256 steps = _mm256_set1_ps(1e6f);
    for (int a = 0; a < 3; ++a) {
        const __m256 far = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_add_epi32(cell[a], r), one));
        const __m256 near = _mm256_cvtepi32_ps(_mm256_sub_epi32(cell[a], r));
        const __m256 up = _mm256_sub_ps(_mm256_sub_ps(far, q[a]), spare);
        const __m256 down = _mm256_sub_ps(_mm256_sub_ps(q[a], near), spare);
        const __m256 ahead = _mm256_cmp_ps(stride[a], zero, _CMP_GT_OQ);
        const __m256 moving = _mm256_cmp_ps(stride[a], zero, _CMP_NEQ_OQ);
        const __m256 room =
            _mm256_mul_ps(_mm256_blendv_ps(down, up, ahead), _mm256_load_ps(inverse[a]));
        steps = _mm256_blendv_ps(steps, _mm256_min_ps(room, steps), moving);
    }
    const __m256i some =
        _mm256_and_si256(_mm256_cmpgt_epi32(c, _mm256_setzero_si256()),
                         _mm256_castps_si256(_mm256_cmp_ps(steps, zero, _CMP_GT_OQ)));
    return _mm256_and_si256(_mm256_cvttps_epi32(steps), some);
}

// The table's colour and opacity at value v in the lanes of `lanes` (not 0):
// FastDvrKernel's lookup and interpolation. Every lane gets a lookup, the
// others at the value of one of `lanes` (eight loads are cheaper than a
// branch per lane, and no cache misses for rows nobody uses).
struct TableLookup {
    const glm::vec4* table;
    float scale, offset, max;
    int lastEntry;
    LUCENT_AVX2 void operator()(__m256 v, int lanes, __m256 c[4]) const {
        const __m256i some = _mm256_set1_epi32(std::countr_zero(unsigned(lanes)));
        v = _mm256_blendv_ps(_mm256_permutevar8x32_ps(v, some), v, laneMask(lanes));
        const __m256 x =
            _mm256_min_ps(_mm256_max_ps(_mm256_add_ps(_mm256_mul_ps(v, _mm256_set1_ps(scale)),
                                                      _mm256_set1_ps(offset)),
                                        _mm256_setzero_ps()),
                          _mm256_set1_ps(max));
        const __m256i e = _mm256_min_epi32(_mm256_cvttps_epi32(x), _mm256_set1_epi32(lastEntry));
        const __m256 f = _mm256_sub_ps(x, _mm256_cvtepi32_ps(e));
        alignas(32) int entry[8];
        alignas(32) float frac[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(entry), e);
        _mm256_store_ps(frac, f);
        alignas(16) glm::vec4 rows[8];
        for (int r = 0; r < 8; ++r) {
            const __m128 t0 = _mm_loadu_ps(&table[entry[r]].x);
            const __m128 t1 = _mm_loadu_ps(&table[entry[r] + 1].x);
            _mm_store_ps(&rows[r].x,
                         _mm_add_ps(t0, _mm_mul_ps(_mm_set1_ps(frac[r]), _mm_sub_ps(t1, t0))));
        }
        transpose(rows, c);
    }
};

// FastDvrKernel::shade for eight lanes (headlight Phong, two-sided).
struct Lighting {
    glm::mat3 toWorld;
    float ambient, diffuse, specular, power;
    bool integer;
    unsigned n;
    LUCENT_AVX2 void operator()(const __m256 grad[3], const __m256 w[3], int bits,
                                __m256 rgb[3]) const {
        __m256 g[3];
        multiply(toWorld, grad, g);
        const __m256 len = _mm256_sqrt_ps(dot(g, g));
        const __m256 lit = _mm256_cmp_ps(len, _mm256_set1_ps(1e-6f), _CMP_NLT_UQ);
        const __m256 absDot = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), dot(g, w)); // |g . w|
        const __m256 ndotl = _mm256_min_ps(_mm256_div_ps(absDot, len), _mm256_set1_ps(1.0f));
        const __m256 diffuseTerm =
            _mm256_add_ps(_mm256_set1_ps(ambient), _mm256_mul_ps(_mm256_set1_ps(diffuse), ndotl));
        __m256 lobe;
        if (integer) {
            lobe = integerPower(ndotl, n);
        } else {
            alignas(32) float x[8], y[8]{};
            _mm256_store_ps(x, ndotl);
            for (int b = bits & maskBits(lit); b != 0; b &= b - 1) {
                const int r = std::countr_zero(unsigned(b));
                y[r] = std::pow(x[r], power);
            }
            lobe = _mm256_load_ps(y);
        }
        const __m256 highlight = _mm256_mul_ps(_mm256_set1_ps(specular), lobe);
        for (int c = 0; c < 3; ++c) {
            const __m256 shaded = _mm256_add_ps(_mm256_mul_ps(rgb[c], diffuseTerm), highlight);
            rgb[c] = _mm256_blendv_ps(rgb[c], shaded, lit);
        }
    }
};

} // namespace lucent::packet
