// Built with -ffp-contract=off (core/raycast/CMakeLists.txt): no multiply-add
// may be fused behind our back, so every float operation rounds as it does in
// FastDvrKernel (built for plain x86-64, which has no FMA).
#include "core/raycast/PacketDvrKernel.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/raycast/PacketRays.h"
#include "core/raycast/PacketSampling.h"

namespace lucent {

bool packetKernelSupported() {
    static const bool supported = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    }();
    return supported;
}

using namespace packet;

template <class T>
LUCENT_AVX2 void PacketDvrKernel<T>::castPacket(const glm::dvec3& o, const glm::dvec3* d,
                                                const glm::dvec3* w, int count,
                                                RayOutput* out) const {
    const FastDvrKernel<T>& k = fast_;
    const RaySetup<float>& s = k.s_;
    const Grid<float, T>& g = k.g_;
    const LinearField<float, T> field{g};
    const T* data = g.data;
    const glm::vec4* table = s.table->data();
    const int lastI = g.nx - 2, lastJ = g.ny - 2, lastK = g.nz - 2;
    const glm::ivec3 cells = s.levels[1].perAxis;
    const int shift = k.fineShift_;
    const float stop = s.earlyTermination;

    PacketRays rays;
    startRays(s, o, d, w, count, rays);
    const LeapLattice& lattice = rays.lattice;
    int active = rays.active;

    const CellClearance clearance(s.invisibleCells);
    // Per lane and axis, 1 / |stride| (clearanceSkip's inverse).
    alignas(32) float inverse[3][kWidth];
    for (int r = 0; r < kWidth; ++r) {
        const glm::vec3 v =
            1.0f / glm::abs(glm::vec3(rays.stride[0][r], rays.stride[1][r], rays.stride[2][r]));
        for (int a = 0; a < 3; ++a) {
            inverse[a][r] = v[a];
        }
    }
    const TableLookup lookup{table, k.tableScale_, k.tableOffset_, k.tableMax_, int(k.lastEntry_)};
    const Lighting light{k.toWorld_,
                         float(s.light.ambient),
                         float(s.light.diffuse),
                         float(s.light.specular),
                         float(s.light.specularPower),
                         k.integerSpecular_,
                         k.specularN_};
    const __m256 dir[3] = {_mm256_load_ps(rays.dir[0]), _mm256_load_ps(rays.dir[1]),
                           _mm256_load_ps(rays.dir[2])};
    __m256 acc[4] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps(),
                     _mm256_setzero_ps()};

    const __m256 vex = _mm256_load_ps(rays.entry[0]), vey = _mm256_load_ps(rays.entry[1]),
                 vez = _mm256_load_ps(rays.entry[2]);
    const __m256 vsx = _mm256_load_ps(rays.stride[0]), vsy = _mm256_load_ps(rays.stride[1]),
                 vsz = _mm256_load_ps(rays.stride[2]);
    const __m256i lastIjk[3] = {_mm256_set1_epi32(lastI), _mm256_set1_epi32(lastJ),
                                _mm256_set1_epi32(lastK)};
    const auto rowStep = std::ptrdiff_t(g.sy), sliceStep = std::ptrdiff_t(g.sz);
    const __m256i rowStride = _mm256_set1_epi32(int(g.sy)),
                  sliceStride = _mm256_set1_epi32(int(g.sz));
    const __m256i cellsX = _mm256_set1_epi32(cells.x), cellsY = _mm256_set1_epi32(cells.y);
    const __m128i shiftCount = _mm_cvtsi32_si128(shift);
    const __m256 visibleLo = _mm256_set1_ps(k.visibleLo_), visibleHi = _mm256_set1_ps(k.visibleHi_);
    __m256i vn = loadInts(rays.first);
    const __m256i vLast = loadInts(rays.last);
    __m256i vChecked = _mm256_set1_epi32(-1); // no cell checked yet
    int emptyBits = 0;                        // lanes whose checked cell can be leapt
    // The cell rows last loaded (for the lanes' cells at `cellAt`), and the
    // gradient corner differences last computed (valid in the lanes
    // `cornersValid`, whose cells were at `cornersAt`): a sample in the same
    // cell as before reads the same voxels, so they are reused as they are.
    // Where every sampling lane lies off the first and last cell along x, the
    // rows are loaded as quads, which hold the gradient's x neighbours too.
    Cell cell;
    RowQuads quads;
    __m256i cellAt = _mm256_set1_epi32(-1), cornersAt = cellAt, quadsAt = cellAt;
    int cornersValid = 0;
    __m256 corners[24];
    std::size_t samples = 0;

    while (active != 0) {
        const __m256 fn = _mm256_cvtepi32_ps(vn);
        const __m256 qx = _mm256_add_ps(vex, _mm256_mul_ps(vsx, fn));
        const __m256 qy = _mm256_add_ps(vey, _mm256_mul_ps(vsy, fn));
        const __m256 qz = _mm256_add_ps(vez, _mm256_mul_ps(vsz, fn));
        __m256i i = _mm256_cvttps_epi32(qx), j = _mm256_cvttps_epi32(qy),
                kk = _mm256_cvttps_epi32(qz);
        // Lanes that sample this pass, and where each lane goes on.
        int sampling = active;
        __m256i next = _mm256_add_epi32(vn, _mm256_set1_epi32(1));
        if (s.leap) {
            const __m256i cy =
                _mm256_add_epi32(_mm256_sra_epi32(j, shiftCount),
                                 _mm256_mullo_epi32(cellsY, _mm256_sra_epi32(kk, shiftCount)));
            const __m256i cell =
                _mm256_add_epi32(_mm256_sra_epi32(i, shiftCount), _mm256_mullo_epi32(cellsX, cy));
            const int same =
                _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(cell, vChecked)));
            // FastDvrKernel's leaping, for all lanes at once. A lane that
            // entered a cell that cannot be leapt samples it; one that entered
            // a leapable cell goes on to the last sample not beyond the exit of
            // the cube (or brick) of leapable cells around it, plus one; one
            // still in the leapable cell it checked goes on by one sample. The
            // other lanes sample in the same pass.
            const int changed = active & ~same;
            const int stepping = active & same & emptyBits;
            if ((changed | stepping) != 0) {
                int leaping = 0, wholeBrick = 0;
                __m256i vReach;
                if (s.cellLeapReach != nullptr) {
                    // Code and reach of every lane that entered a cell, in one
                    // gather and no branch per lane (active lanes' cells are
                    // inside the grid; the others are masked off).
                    const __m256i both = _mm256_mask_i32gather_epi32(
                        _mm256_setzero_si256(),
                        reinterpret_cast<const int*>(s.cellLeapReach->data()), cell,
                        _mm256_castps_si256(laneMask(changed)), 4);
                    const __m256i code = _mm256_and_si256(both, _mm256_set1_epi32(0xff));
                    leaping = changed & ~maskBits(_mm256_cmpeq_epi32(code, _mm256_setzero_si256()));
                    wholeBrick = changed & maskBits(_mm256_cmpeq_epi32(code, _mm256_set1_epi32(2)));
                    vReach = _mm256_srli_epi32(both, 8);
                } else {
                    alignas(32) int entered[kWidth], reach[kWidth]{};
                    storeInts(entered, cell);
                    for (int bits = changed; bits != 0; bits &= bits - 1) {
                        const int r = std::countr_zero(unsigned(bits));
                        const std::uint8_t code = (*s.cellLeap)[std::size_t(entered[r])];
                        if (code != 0) {
                            leaping |= 1 << r;
                            wholeBrick |= code == 2 ? 1 << r : 0;
                            reach[r] = s.cellReach != nullptr
                                           ? (*s.cellReach)[std::size_t(entered[r])]
                                           : 0;
                        }
                    }
                    vReach = loadInts(reach);
                }
                vChecked =
                    _mm256_blendv_epi8(vChecked, cell, _mm256_castps_si256(laneMask(changed)));
                emptyBits = (emptyBits & ~changed) | leaping;
                if ((leaping | stepping) != 0) {
                    sampling &= ~stepping;
                    if (leaping != 0) {
                        const __m256i one = _mm256_set1_epi32(1);
                        const __m256i ijk[3] = {i, j, kk};
                        __m256i lo[3], hi[3];
                        for (int a = 0; a < 3; ++a) {
                            const __m256i c = _mm256_sra_epi32(ijk[a], shiftCount);
                            lo[a] = _mm256_sub_epi32(c, vReach);
                            hi[a] = _mm256_add_epi32(c, vReach);
                        }
                        __m256d exit[2];
                        boxExits(lo, hi, s.levels[1].size, cells, lattice, exit);
                        if (wholeBrick != 0) {
                            const auto& brick = s.levels[0];
                            alignas(32) int at[3][kWidth], b[3][kWidth]{};
                            storeInts(at[0], i);
                            storeInts(at[1], j);
                            storeInts(at[2], kk);
                            for (int bits = wholeBrick; bits != 0; bits &= bits - 1) {
                                const int r = std::countr_zero(unsigned(bits));
                                for (int a = 0; a < 3; ++a) {
                                    b[a][r] = std::min(at[a][r] / brick.size, brick.perAxis[a] - 1);
                                }
                            }
                            __m256i vb[3];
                            for (int a = 0; a < 3; ++a) {
                                vb[a] = loadInts(b[a]);
                            }
                            __m256d brickExit[2];
                            boxExits(vb, vb, brick.size, brick.perAxis, lattice, brickExit);
                            for (int h = 0; h < 2; ++h) {
                                const int bitsH = (wholeBrick >> (4 * h)) & 15;
                                const __m256d whole = _mm256_castsi256_pd(_mm256_cmpeq_epi64(
                                    _mm256_and_si256(_mm256_set1_epi64x(bitsH),
                                                     _mm256_setr_epi64x(1, 2, 4, 8)),
                                    _mm256_setr_epi64x(1, 2, 4, 8)));
                                exit[h] = _mm256_blendv_pd(
                                    exit[h], _mm256_max_pd(exit[h], brickExit[h]), whole);
                            }
                        }
                        // A negative exit (rounding) means the cell is sampled after
                        // all; else the lane goes on at max(n, long(exit)) + 1, the
                        // first sample beyond the exit (FastDvrKernel::cast says why).
                        __m128i whole[2];
                        int ahead = 0;
                        for (int h = 0; h < 2; ++h) {
                            ahead |= _mm256_movemask_pd(
                                         _mm256_cmp_pd(exit[h], _mm256_setzero_pd(), _CMP_GE_OQ))
                                     << (4 * h);
                            whole[h] =
                                _mm256_cvttpd_epi32(_mm256_min_pd(exit[h], _mm256_set1_pd(2e9)));
                        }
                        const __m256i resume = _mm256_add_epi32(
                            _mm256_max_epi32(vn, _mm256_set_m128i(whole[1], whole[0])), one);
                        emptyBits &= ~(leaping & ~ahead);
                        next = _mm256_blendv_epi8(next, resume,
                                                  _mm256_castps_si256(laneMask(leaping & ahead)));
                        sampling &= ~(leaping & ahead);
                    }
                }
            }
        }
        if (sampling != 0) {
            samples += std::size_t(std::popcount(unsigned(sampling)));
            // Rays that are done may lie anywhere: clamping keeps their reads inside.
            i = clampInt(i, lastIjk[0]);
            j = clampInt(j, lastIjk[1]);
            kk = clampInt(kk, lastIjk[2]);
            // A lane in a cell no sample can see is taken as transparent
            // without reading its voxels.
            if (clearance.words != nullptr) {
                const __m256i c = clearance(i, j, kk, sampling);
                const __m256i clear = _mm256_cmpgt_epi32(c, _mm256_setzero_si256());
                if (maskBits(clear) != 0) {
                    const __m256i cellIjk[3] = {i, j, kk};
                    const __m256 q[3] = {qx, qy, qz}, stride[3] = {vsx, vsy, vsz};
                    next = _mm256_add_epi32(next, clearanceSkips(q, cellIjk, c, stride, inverse));
                    sampling &= ~maskBits(clear);
                }
            }
        }
        if (sampling != 0) {
            const __m256 fx = _mm256_sub_ps(qx, _mm256_cvtepi32_ps(i));
            const __m256 fy = _mm256_sub_ps(qy, _mm256_cvtepi32_ps(j));
            const __m256 fz = _mm256_sub_ps(qz, _mm256_cvtepi32_ps(kk));
            const __m256i o00 =
                _mm256_add_epi32(i, _mm256_add_epi32(_mm256_mullo_epi32(j, rowStride),
                                                     _mm256_mullo_epi32(kk, sliceStride)));
            // Lanes that do not sample read a sampling lane's voxels (no cache
            // misses for voxels nobody uses); their rows then belong to no cell.
            const __m256i samplingLanes = _mm256_castps_si256(laneMask(sampling));
            const __m256i some = _mm256_set1_epi32(std::countr_zero(unsigned(sampling)));
            alignas(32) int offset[kWidth];
            storeInts(offset, _mm256_blendv_epi8(_mm256_permutevar8x32_epi32(o00, some), o00,
                                                 samplingLanes));
            const T* base[kWidth];
            for (int r = 0; r < kWidth; ++r) {
                base[r] = data + offset[r];
            }
            if ((sampling & ~maskBits(_mm256_cmpeq_epi32(o00, cellAt))) != 0) {
                cellAt =
                    _mm256_or_si256(o00, _mm256_andnot_si256(samplingLanes, _mm256_set1_epi32(-1)));
                const int offX =
                    maskBits(_mm256_and_si256(_mm256_cmpgt_epi32(i, _mm256_setzero_si256()),
                                              _mm256_cmpgt_epi32(lastIjk[0], i)));
                if ((sampling & ~offX) == 0) {
                    loadRowQuads(base, rowStep, sliceStep, quads);
                    cellOf(quads, cell);
                    quadsAt = cellAt;
                } else {
                    for (int r = 0; r < 4; ++r) {
                        cell.row[r] = pairAt(base, ((r & 1) != 0 ? rowStep : 0) +
                                                       ((r & 2) != 0 ? sliceStep : 0));
                    }
                    quadsAt = _mm256_set1_epi32(-1);
                }
            }
            // The same operations, in the same order, as FastDvrKernel's.
            const __m256 c00 = lerp(cell.row[0].a, cell.row[0].b, fx);
            const __m256 c10 = lerp(cell.row[1].a, cell.row[1].b, fx);
            const __m256 c01 = lerp(cell.row[2].a, cell.row[2].b, fx);
            const __m256 c11 = lerp(cell.row[3].a, cell.row[3].b, fx);
            const __m256 v = lerp(lerp(c00, c10, fy), lerp(c01, c11, fy), fz);
            const __m256 inRange = _mm256_and_ps(_mm256_cmp_ps(v, visibleLo, _CMP_GE_OQ),
                                                 _mm256_cmp_ps(v, visibleHi, _CMP_LE_OQ));
            const int visible = sampling & _mm256_movemask_ps(inRange);
            __m256 c[4];
            const int contributing =
                visible == 0
                    ? 0
                    : (lookup(v, visible, c),
                       visible & maskBits(_mm256_cmp_ps(c[3], _mm256_setzero_ps(), _CMP_GT_OQ)));
            if (contributing != 0) {
                if (s.shading) {
                    const __m256i inside = _mm256_and_si256(
                        _mm256_and_si256(
                            _mm256_cmpgt_epi32(_mm256_min_epi32(i, _mm256_min_epi32(j, kk)),
                                               _mm256_setzero_si256()),
                            _mm256_cmpgt_epi32(lastIjk[0], i)),
                        _mm256_and_si256(_mm256_cmpgt_epi32(lastIjk[1], j),
                                         _mm256_cmpgt_epi32(lastIjk[2], kk)));
                    const int insideBits = contributing & maskBits(inside);
                    __m256 grad[3];
                    if (insideBits != 0) {
                        const int same =
                            cornersValid & maskBits(_mm256_cmpeq_epi32(o00, cornersAt));
                        if ((insideBits & ~same) != 0) {
                            // The corners of the lanes that shade inside the volume;
                            // the others read one of theirs (no cache misses for
                            // voxels nobody shades), and lanes at the border take
                            // the clamped filter's gradient below.
                            const int valid = insideBits;
                            const T* at[kWidth];
                            const T* some = base[std::countr_zero(unsigned(insideBits))];
                            for (int r = 0; r < kWidth; ++r) {
                                at[r] = (valid >> r & 1) != 0 ? base[r] : some;
                            }
                            if ((valid & ~maskBits(_mm256_cmpeq_epi32(o00, quadsAt))) != 0) {
                                loadRowQuads(at, rowStep, sliceStep, quads);
                                quadsAt = _mm256_set1_epi32(-1); // not the cells' rows
                            }
                            gradientCorners(at, cell, quads, rowStep, sliceStep, corners);
                            cornersAt = o00;
                            cornersValid = valid;
                        }
                        blendGradient(corners, fx, fy, fz, grad);
                    }
                    if (const int border = contributing & ~insideBits; border != 0) {
                        alignas(32) float px[kWidth], py[kWidth], pz[kWidth], gs[3][kWidth]{};
                        _mm256_store_ps(px, qx);
                        _mm256_store_ps(py, qy);
                        _mm256_store_ps(pz, qz);
                        for (int a = 0; a < 3 && insideBits != 0; ++a) {
                            _mm256_store_ps(gs[a], grad[a]);
                        }
                        for (int b = border; b != 0; b &= b - 1) {
                            const int r = std::countr_zero(unsigned(b));
                            const glm::vec3 gr = field.gradient(glm::vec3(px[r], py[r], pz[r]));
                            gs[0][r] = gr.x, gs[1][r] = gr.y, gs[2][r] = gr.z;
                        }
                        for (int a = 0; a < 3; ++a) {
                            grad[a] = _mm256_load_ps(gs[a]);
                        }
                    }
                    light(grad, dir, contributing, c);
                }
                // Front to back, in the lanes that add something.
                const __m256 adds = laneMask(contributing);
                const __m256 weight =
                    _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(1.0f), acc[3]), c[3]);
                for (int ch = 0; ch < 3; ++ch) {
                    acc[ch] = _mm256_blendv_ps(
                        acc[ch], _mm256_add_ps(acc[ch], _mm256_mul_ps(weight, c[ch])), adds);
                }
                acc[3] = _mm256_blendv_ps(acc[3], _mm256_add_ps(acc[3], weight), adds);
                active &= ~(contributing &
                            maskBits(_mm256_cmp_ps(acc[3], _mm256_set1_ps(stop), _CMP_GE_OQ)));
            }
        }
        vn = next;
        active &= ~_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(vn, vLast)));
    }

    alignas(32) float rgba[4][kWidth];
    for (int ch = 0; ch < 4; ++ch) {
        _mm256_store_ps(rgba[ch], acc[ch]);
    }
    for (int r = 0; r < count; ++r) {
        out[r].rgba = glm::dvec4(rgba[0][r], rgba[1][r], rgba[2][r], rgba[3][r]);
        out[r].samples = r == 0 ? samples : 0;
    }
}

template class PacketDvrKernel<std::int16_t>;
template class PacketDvrKernel<std::uint16_t>;
template class PacketDvrKernel<float>;

} // namespace lucent
