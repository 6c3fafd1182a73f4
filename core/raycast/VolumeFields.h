#pragma once
// The three reconstruction filters the ray casters sample with, each giving a
// value and a gradient (in index space) from the same filter. Positions are
// continuous voxel indices, clamped to the volume.

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <glm/glm.hpp>

namespace lucent {

template <class Real> using Vec3 = glm::vec<3, Real>;

template <class Real, class T> struct Grid {
    const T* data = nullptr;
    int nx = 0, ny = 0, nz = 0;
    std::size_t sy = 0, sz = 0;

    Grid() = default;
    Grid(const T* d, glm::ivec3 dims)
        : data(d), nx(dims.x), ny(dims.y), nz(dims.z), sy(std::size_t(dims.x)),
          sz(std::size_t(dims.x) * dims.y) {}
    // Asks for the cache lines a sample at p will read (rows j, j+1 of slices k, k+1).
    void prefetch(const Vec3<Real>& p) const {
        const int i = std::clamp(int(p.x), 0, nx - 1), j = std::clamp(int(p.y), 0, ny - 1),
                  k = std::clamp(int(p.z), 0, nz - 1);
        const T* d = data + std::size_t(i) + sy * j + sz * k;
        __builtin_prefetch(d);
        if (j + 1 < ny) {
            __builtin_prefetch(d + sy);
        }
        if (k + 1 < nz) {
            __builtin_prefetch(d + sz);
            if (j + 1 < ny) {
                __builtin_prefetch(d + sz + sy);
            }
        }
    }
    Real at(int i, int j, int k) const {
        i = std::clamp(i, 0, nx - 1);
        j = std::clamp(j, 0, ny - 1);
        k = std::clamp(k, 0, nz - 1);
        return static_cast<Real>(data[std::size_t(i) + sy * j + sz * k]);
    }
};

template <class Real, class T> struct NearestField {
    static constexpr bool isNearest = true;
    Grid<Real, T> g;
    Real value(const Vec3<Real>& p) const {
        return g.at(int(std::lround(p.x)), int(std::lround(p.y)), int(std::lround(p.z)));
    }
    // Inside the box p >= 0 (up to rounding), so adding a half and truncating rounds.
    Real valueInside(const Vec3<Real>& p) const {
        return g.at(int(p.x + Real(0.5)), int(p.y + Real(0.5)), int(p.z + Real(0.5)));
    }
    Vec3<Real> gradient(const Vec3<Real>& p) const {
        const int i = int(std::lround(p.x)), j = int(std::lround(p.y)), k = int(std::lround(p.z));
        return Vec3<Real>(g.at(i + 1, j, k) - g.at(i - 1, j, k),
                          g.at(i, j + 1, k) - g.at(i, j - 1, k),
                          g.at(i, j, k + 1) - g.at(i, j, k - 1)) *
               Real(0.5);
    }
};

template <class Real, class T> struct LinearField {
    static constexpr bool isNearest = false;
    Grid<Real, T> g;
    Real value(const Vec3<Real>& p) const {
        return valueInside(glm::clamp(p, Vec3<Real>(0), Vec3<Real>(g.nx - 1, g.ny - 1, g.nz - 1)));
    }
    // For positions inside [0, dims-1] (up to rounding): no clamping of coordinates.
    Real valueInside(const Vec3<Real>& p) const {
        const int i = std::min(int(p.x), std::max(g.nx - 2, 0));
        const int j = std::min(int(p.y), std::max(g.ny - 2, 0));
        const int k = std::min(int(p.z), std::max(g.nz - 2, 0));
        const Real fx = p.x - Real(i), fy = p.y - Real(j), fz = p.z - Real(k);
        const T* d = g.data + std::size_t(i) + g.sy * j + g.sz * k;
        const std::size_t dx = g.nx > 1 ? 1 : 0, dy = g.ny > 1 ? g.sy : 0, dz = g.nz > 1 ? g.sz : 0;
        const Real c00 = Real(d[0]) + fx * (Real(d[dx]) - Real(d[0]));
        const Real c10 = Real(d[dy]) + fx * (Real(d[dy + dx]) - Real(d[dy]));
        const Real c01 = Real(d[dz]) + fx * (Real(d[dz + dx]) - Real(d[dz]));
        const Real c11 = Real(d[dz + dy]) + fx * (Real(d[dz + dy + dx]) - Real(d[dz + dy]));
        const Real c0 = c00 + fy * (c10 - c00);
        const Real c1 = c01 + fy * (c11 - c01);
        return c0 + fz * (c1 - c0);
    }
    // Central differences of the trilinear field, one voxel apart.
    Vec3<Real> gradient(const Vec3<Real>& p) const {
        const Vec3<Real> ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
        return Vec3<Real>(value(p + ex) - value(p - ex), value(p + ey) - value(p - ey),
                          value(p + ez) - value(p - ez)) *
               Real(0.5);
    }
};

// Cubic B-spline on prefiltered coefficients: interpolating, C2, and its
// gradient is the exact derivative of the same spline.
template <class Real> struct CubicField {
    static constexpr bool isNearest = false;
    Grid<Real, Real> g;

    static void weights(Real t, Real w[4], Real dw[4]) {
        const Real t2 = t * t, t3 = t2 * t, s = Real(1) - t;
        w[0] = s * s * s / Real(6);
        w[1] = (Real(3) * t3 - Real(6) * t2 + Real(4)) / Real(6);
        w[2] = (Real(-3) * t3 + Real(3) * t2 + Real(3) * t + Real(1)) / Real(6);
        w[3] = t3 / Real(6);
        dw[0] = -s * s / Real(2);
        dw[1] = (Real(3) * t2 - Real(4) * t) / Real(2);
        dw[2] = (Real(-3) * t2 + Real(2) * t + Real(1)) / Real(2);
        dw[3] = t2 / Real(2);
    }

    template <bool WithGradient> Real evaluate(const Vec3<Real>& p, Vec3<Real>* grad) const {
        const Real x = std::clamp(p.x, Real(0), Real(g.nx - 1));
        const Real y = std::clamp(p.y, Real(0), Real(g.ny - 1));
        const Real z = std::clamp(p.z, Real(0), Real(g.nz - 1));
        const int i = int(std::floor(x)), j = int(std::floor(y)), k = int(std::floor(z));
        Real wx[4], wy[4], wz[4], dx[4], dy[4], dz[4];
        weights(x - Real(i), wx, dx);
        weights(y - Real(j), wy, dy);
        weights(z - Real(k), wz, dz);
        Real v = 0, gx = 0, gy = 0, gz = 0;
        for (int c = 0; c < 4; ++c) {
            Real vy = 0, gyy = 0, gxy = 0;
            for (int b = 0; b < 4; ++b) {
                Real vx = 0, gxx = 0;
                for (int a = 0; a < 4; ++a) {
                    const Real coef = mirrored(i + a - 1, j + b - 1, k + c - 1);
                    vx += wx[a] * coef;
                    if constexpr (WithGradient) {
                        gxx += dx[a] * coef;
                    }
                }
                vy += wy[b] * vx;
                if constexpr (WithGradient) {
                    gyy += dy[b] * vx;
                    gxy += wy[b] * gxx;
                }
            }
            v += wz[c] * vy;
            if constexpr (WithGradient) {
                gz += dz[c] * vy;
                gy += wz[c] * gyy;
                gx += wz[c] * gxy;
            }
        }
        if constexpr (WithGradient) {
            *grad = Vec3<Real>(gx, gy, gz);
        }
        return v;
    }

    // Coefficients beyond the edge mirror those inside (the prefilter's boundary condition).
    Real mirrored(int i, int j, int k) const {
        return g.at(mirror(i, g.nx), mirror(j, g.ny), mirror(k, g.nz));
    }
    static int mirror(int i, int n) {
        if (n == 1) {
            return 0;
        }
        const int period = 2 * (n - 1);
        i = ((i % period) + period) % period;
        return i < n ? i : period - i;
    }

    Real value(const Vec3<Real>& p) const { return evaluate<false>(p, nullptr); }
    Real valueInside(const Vec3<Real>& p) const { return value(p); }
    Vec3<Real> gradient(const Vec3<Real>& p) const {
        Vec3<Real> grad;
        evaluate<true>(p, &grad);
        return grad;
    }
};

} // namespace lucent
