#pragma once
// The CPU ray caster's common case in one tight loop: direct volume rendering,
// float precision, post-classification through the table, trilinear, no
// pre-integration. It takes exactly the samples RayKernel takes (the lattice
// of RenderDescription.h, the same leaping decisions), with float arithmetic
// per sample, cell changes found from the voxel index the trilinear filter
// needs anyway, and gradients from one pass over the 32 voxels the six
// trilinear fetches of the central differences share. Private to core/raycast.

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/raycast/InvisibleCells.h"
#include "core/raycast/RaySetup.h"
#include "core/raycast/VolumeFields.h"

namespace lucent {

// x^n by squaring (n small): the specular term's usual integer exponents.
inline float integerPower(float x, unsigned n) {
    float r = 1.0f;
    while (n != 0u) {
        if ((n & 1u) != 0u) {
            r *= x;
        }
        x *= x;
        n >>= 1u;
    }
    return r;
}

// How many lattice samples after one at p, in cell `cell` of clearance c >= 1
// (InvisibleCells), stay within c - 1 cells of it with 0.01 voxel to spare for
// float rounding: the ray passes over them. inverse[a] = 1 / |stride[a]|.
inline int clearanceSkip(const glm::vec3& p, const glm::ivec3& cell, int c, const glm::vec3& stride,
                         const glm::vec3& inverse) {
    float steps = 1e6f;
    const int r = c - 1;
    for (int a = 0; a < 3; ++a) {
        if (stride[a] > 0.0f) {
            steps = std::min(steps, ((float(cell[a] + r + 1) - p[a]) - 0.01f) * inverse[a]);
        } else if (stride[a] < 0.0f) {
            steps = std::min(steps, ((p[a] - float(cell[a] - r)) - 0.01f) * inverse[a]);
        }
    }
    return steps > 0.0f ? int(steps) : 0;
}

template <class T> class PacketDvrKernel;

template <class T> class FastDvrKernel {
    static constexpr int kPrefetchAhead = 16;
    friend class PacketDvrKernel<T>; // marches eight rays with this kernel's per-sample steps

public:
    // Whether the fast kernel renders `s` over a volume of `dims` exactly as
    // RayKernel<float, LinearField> would (up to float rounding of the lookups).
    static bool applies(const RaySetup<float>& s, glm::ivec3 dims) {
        const int fine = s.levels[1].size;
        return s.mode == RenderMode::Dvr && s.classification == Classification::Post &&
               !s.preintegrate && !s.exactTf && s.table != nullptr &&
               (!s.leap || s.cellLeap != nullptr) && dims.x >= 3 && dims.y >= 3 && dims.z >= 3 &&
               (!s.leap || std::has_single_bit(unsigned(fine)));
    }

    FastDvrKernel(const RaySetup<float>& s, const Grid<float, T>& g) : s_(s), g_(g) {
        toWorld_ = glm::mat3(s.gradientToWorld);
        const double scale = s.tableScale;
        tableScale_ = float(scale);
        tableOffset_ = float(-s.tableLo * scale);
        tableMax_ = float(s.table->size() - 1);
        lastEntry_ = s.table->size() - 2;
        visibleLo_ = float(s.visibleLo);
        visibleHi_ = float(s.visibleHi);
        const double power = s.light.specularPower;
        integerSpecular_ = power >= 0.0 && power <= 64.0 && power == std::floor(power);
        specularN_ = integerSpecular_ ? unsigned(power) : 0u;
        fineShift_ = std::countr_zero(unsigned(s.levels[1].size));
    }

    RayOutput cast(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& w) const;

private:
    // Central differences of the trilinear field at a sample whose cell is
    // (i, j, k), weights fx, fy, fz, all neighbours inside the volume.
    glm::vec3 gradientInside(const T* v, float fx, float fy, float fz) const;
    glm::vec3 shade(const glm::vec3& base, const glm::vec3& grad, const glm::vec3& w) const;
    struct Lattice {
        glm::dvec3 entry, stride, inverse; // p(n) = entry + stride * n
    };
    // In lattice units, where the ray leaves the leapable cells or brick
    // around voxel (i, j, k), or -1 when its cell cannot be leapt.
    [[gnu::always_inline]] double leapExit(int i, int j, int k, int fine, const Lattice& l) const;
    // In lattice units, where the ray leaves cells lo .. hi (inclusive) of
    // `level`; no limit along axes where they reach the end of the grid.
    [[gnu::always_inline]] double boxExit(glm::ivec3 lo, glm::ivec3 hi,
                                          const typename RaySetup<float>::LeapLevel& level,
                                          const Lattice& l) const;

    const RaySetup<float>& s_;
    Grid<float, T> g_;
    glm::mat3 toWorld_{1.0f};
    float tableScale_ = 1.0f, tableOffset_ = 0.0f, tableMax_ = 0.0f;
    std::size_t lastEntry_ = 0;
    float visibleLo_ = 0.0f, visibleHi_ = 0.0f;
    bool integerSpecular_ = false;
    unsigned specularN_ = 0;
    int fineShift_ = 3;
};

template <class T>
glm::vec3 FastDvrKernel<T>::gradientInside(const T* v, float fx, float fy, float fz) const {
    const std::size_t sy = g_.sy, sz = g_.sz;
    auto f = [](T x) { return float(x); };
    auto lerp = [](float a, float b, float t) { return a + t * (b - a); };
    // d(c) = value(c + e) - value(c - e) at the eight corners, then trilinear.
    auto axis = [&](std::size_t e) {
        float c[8];
        for (int n = 0; n < 8; ++n) {
            const T* p = v + std::size_t(n & 1) + ((n & 2) != 0 ? sy : 0) + ((n & 4) != 0 ? sz : 0);
            c[n] = f(p[e]) - f(p[-std::ptrdiff_t(e)]);
        }
        const float c0 = lerp(lerp(c[0], c[1], fx), lerp(c[2], c[3], fx), fy);
        const float c1 = lerp(lerp(c[4], c[5], fx), lerp(c[6], c[7], fx), fy);
        return lerp(c0, c1, fz);
    };
    return glm::vec3(axis(1), axis(sy), axis(sz)) * 0.5f;
}

template <class T>
glm::vec3 FastDvrKernel<T>::shade(const glm::vec3& base, const glm::vec3& grad,
                                  const glm::vec3& w) const {
    const glm::vec3 g = toWorld_ * grad;
    const float len = std::sqrt(glm::dot(g, g));
    if (len < 1e-6f) {
        return base; // no surface to light: a homogeneous region keeps its colour
    }
    // Headlight: L = V = H = -w; two-sided.
    const float ndotl = std::min(1.0f, std::abs(glm::dot(g, w)) / len);
    const float diffuse = float(s_.light.ambient) + float(s_.light.diffuse) * ndotl;
    const float lobe = integerSpecular_ ? integerPower(ndotl, specularN_)
                                        : std::pow(ndotl, float(s_.light.specularPower));
    return base * diffuse + glm::vec3(float(s_.light.specular) * lobe);
}

template <class T>
inline double FastDvrKernel<T>::boxExit(glm::ivec3 lo, glm::ivec3 hi,
                                        const typename RaySetup<float>::LeapLevel& level,
                                        const Lattice& l) const {
    double exit = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (l.stride[a] > 1e-15 && hi[a] < level.perAxis[a] - 1) {
            exit = std::min(exit, (double((hi[a] + 1) * level.size) - l.entry[a]) * l.inverse[a]);
        } else if (l.stride[a] < -1e-15 && lo[a] > 0) {
            exit = std::min(exit, (double(lo[a] * level.size) - l.entry[a]) * l.inverse[a]);
        }
    }
    return exit;
}

template <class T>
inline double FastDvrKernel<T>::leapExit(int i, int j, int k, int fine, const Lattice& l) const {
    const std::uint8_t code = (*s_.cellLeap)[std::size_t(fine)];
    if (code == 0) {
        return -1.0;
    }
    // The cube of leapable cells around this one, or the brick where it
    // reaches further: the ray stays in either until it leaves it.
    const int reach = s_.cellReach != nullptr ? (*s_.cellReach)[std::size_t(fine)] : 0;
    const glm::ivec3 cell = glm::ivec3(i, j, k) >> fineShift_;
    double exit = boxExit(cell - reach, cell + reach, s_.levels[1], l);
    if (code == 2) {
        const auto& brick = s_.levels[0];
        const glm::ivec3 b = glm::min(glm::ivec3(i, j, k) / brick.size, brick.perAxis - 1);
        exit = std::max(exit, boxExit(b, b, brick, l));
    }
    return exit;
}

template <class T>
RayOutput FastDvrKernel<T>::cast(const glm::dvec3& o, const glm::dvec3& d,
                                 const glm::dvec3& w) const {
    RayOutput out;
    RaySpan span;
    if (!raySpan(s_, o, d, span)) {
        return out;
    }
    const double t0 = span.t0, dt = s_.dt;
    // The lattice: p(n) = entry + stride * n, the same formula as RayKernel.
    const glm::vec3 entry(o + d * t0), stride(d * dt), wf(w);
    const glm::vec3 inverseStride = 1.0f / glm::abs(stride);
    const InvisibleCells* invisible = s_.invisibleCells;
    Lattice lattice{o + d * t0, d * dt, glm::dvec3(0.0)};
    for (int a = 0; a < 3; ++a) {
        lattice.inverse[a] = std::abs(lattice.stride[a]) > 1e-15 ? 1.0 / lattice.stride[a] : 0.0;
    }
    const T* data = g_.data;
    const std::size_t sy = g_.sy, sz = g_.sz;
    const int lastI = g_.nx - 2, lastJ = g_.ny - 2, lastK = g_.nz - 2;
    const glm::ivec3 cellsPerAxis = s_.levels[1].perAxis;
    const glm::vec4* table = s_.table->data();
    const bool leap = s_.leap, shading = s_.shading;
    const float stop = s_.earlyTermination;
    const LinearField<float, T> field{g_};
    float accR = 0, accG = 0, accB = 0, accA = 0;
    int checkedCell = -1;
    bool checkedEmpty = false;
    std::size_t samples = 0;

    for (long n = span.nFirst; n <= span.nLast; ++n) {
        const float fn = float(n);
        const float px = entry.x + stride.x * fn, py = entry.y + stride.y * fn,
                    pz = entry.z + stride.z * fn;
        // Samples lie inside the box (p >= 0 up to rounding): truncation is floor.
        int i = int(px), j = int(py), k = int(pz);
        if (leap) {
            const int cell =
                (i >> fineShift_) +
                cellsPerAxis.x * ((j >> fineShift_) + cellsPerAxis.y * (k >> fineShift_));
            if (cell == checkedCell) {
                if (checkedEmpty) {
                    continue; // a sample in a cell that cannot be seen
                }
            } else {
                checkedCell = cell;
                const double exit = leapExit(i, j, k, cell, lattice);
                checkedEmpty = exit >= 0.0;
                if (checkedEmpty) {
                    // Resume at the first lattice sample beyond the exit. The
                    // last one not beyond it lies in the leapable box up to
                    // float rounding of positions, which the cells' second
                    // voxel of overlap covers: it is passed over as well.
                    n = exit >= double(span.nLast) ? span.nLast : std::max(n, long(exit));
                    continue;
                }
            }
        }
        ++samples;
        // Volume reads along a ray miss the cache; ask for them well ahead.
        const float fa = fn + float(kPrefetchAhead);
        g_.prefetch(
            glm::vec3(entry.x + stride.x * fa, entry.y + stride.y * fa, entry.z + stride.z * fa));
        i = std::min(i, lastI);
        j = std::min(j, lastJ);
        k = std::min(k, lastK);
        if (invisible != nullptr) {
            if (const int c = invisible->clearance({i, j, k}); c != 0) {
                // Transparent, and so are the samples that follow in cells as clear.
                n += clearanceSkip(glm::vec3(px, py, pz), glm::ivec3(i, j, k), c, stride,
                                   inverseStride);
                continue;
            }
        }
        const float fx = px - float(i), fy = py - float(j), fz = pz - float(k);
        const T* v = data + std::size_t(i) + sy * std::size_t(j) + sz * std::size_t(k);
        // The same operations, in the same order, as LinearField::valueInside.
        const float c00 = float(v[0]) + fx * (float(v[1]) - float(v[0]));
        const float c10 = float(v[sy]) + fx * (float(v[sy + 1]) - float(v[sy]));
        const float c01 = float(v[sz]) + fx * (float(v[sz + 1]) - float(v[sz]));
        const float c11 = float(v[sz + sy]) + fx * (float(v[sz + sy + 1]) - float(v[sz + sy]));
        const float c0 = c00 + fy * (c10 - c00);
        const float c1 = c01 + fy * (c11 - c01);
        const float value = c0 + fz * (c1 - c0);
        if (!(value >= visibleLo_ && value <= visibleHi_)) {
            continue; // transparent: no table lookup, no shading
        }
        const float x = std::clamp(value * tableScale_ + tableOffset_, 0.0f, tableMax_);
        const std::size_t e = std::min(static_cast<std::size_t>(x), lastEntry_);
        const float f = x - float(e);
        const glm::vec4 c = table[e] + f * (table[e + 1] - table[e]);
        if (c.a <= 0.0f) {
            continue;
        }
        glm::vec3 rgb(c);
        if (shading) {
            const bool inside = i >= 1 && j >= 1 && k >= 1 && i < lastI && j < lastJ && k < lastK;
            const glm::vec3 grad =
                inside ? gradientInside(v, fx, fy, fz) : field.gradient(glm::vec3(px, py, pz));
            rgb = shade(rgb, grad, wf);
        }
        const float weight = (1.0f - accA) * c.a;
        accR += weight * rgb.r;
        accG += weight * rgb.g;
        accB += weight * rgb.b;
        accA += weight;
        if (accA >= stop) {
            break;
        }
    }
    out.samples = samples;
    out.rgba = glm::dvec4(accR, accG, accB, accA);
    return out;
}

} // namespace lucent
