#pragma once
// Volumes to contour in the surface tests: fields sampled at the voxels'
// patient positions (signed distance of a sphere, a binary ball, several
// balls), and noise.

#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <random>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/surface/IsosurfaceExtractor.h"
#include "core/surface/MarchingCubesTable.h"
#include "core/volume/Volume.h"

namespace lucent::test {

// f evaluated at every voxel's LPS position, rounded for integer voxel types.
inline Volume sampledVolume(const VolumeGeometry& g, VoxelType type,
                            const std::function<double(const glm::dvec3&)>& f) {
    Volume v(g, type);
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const double value = f(g.toPatient(glm::dvec3(i, j, k)));
                const std::size_t n = v.linearIndex(i, j, k);
                visitVoxels(v, [&](auto voxels) {
                    using T = typename decltype(voxels)::element_type;
                    voxels[n] = std::is_integral_v<T> ? T(std::lround(value)) : T(value);
                });
            }
        }
    }
    return v;
}

// An n^3 grid of spacing h whose voxel centres are symmetric about `centre`.
inline VolumeGeometry cubeAround(glm::dvec3 centre, int n, double h) {
    VolumeGeometry g;
    g.dims = glm::ivec3(n);
    g.spacing = glm::dvec3(h);
    g.origin = centre - 0.5 * h * (n - 1);
    return g;
}

// The centre of the test spheres: off the grid nodes of cubeAround(origin, ...),
// whose voxel centres are symmetric about the origin.
inline const glm::dvec3 kSphereCentre{0.31, -0.17, 0.23};

// Signed distance a - |x - c| (positive inside), float, margin of 3 voxels.
inline Volume sphereDistance(double a, double h) {
    const int n = static_cast<int>(std::ceil(2.0 * a / h)) + 7;
    return sampledVolume(cubeAround(glm::dvec3(0.0), n, h), VoxelType::Float32,
                         [a](const glm::dvec3& x) { return a - glm::length(x - kSphereCentre); });
}

// 1 inside the ball of radius a about kSphereCentre, 0 outside (uint16).
inline Volume binaryBall(double a, double h) {
    const int n = static_cast<int>(std::ceil(2.0 * a / h)) + 7;
    return sampledVolume(cubeAround(glm::dvec3(0.0), n, h), VoxelType::UInt16,
                         [a](const glm::dvec3& x) { return glm::length(x - kSphereCentre) <= a; });
}

inline double sphereArea(double a) {
    return 4.0 * std::numbers::pi * a * a;
}
inline double sphereVolume(double a) {
    return 4.0 / 3.0 * std::numbers::pi * a * a * a;
}

// Independent standard normal values on an n^3 unit grid.
inline Volume gaussianNoise(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal;
    VolumeGeometry g;
    g.dims = glm::ivec3(n);
    return sampledVolume(g, VoxelType::Float32, [&](const glm::dvec3&) { return normal(rng); });
}

// Uniform integers in [lo, hi] on an n^3 unit grid, int16.
inline Volume integerNoise(int n, int lo, int hi, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> uniform(lo, hi);
    VolumeGeometry g;
    g.dims = glm::ivec3(n);
    return sampledVolume(g, VoxelType::Int16, [&](const glm::dvec3&) { return uniform(rng); });
}

// Triangles and vertices by brute force, independent of the extractor's
// bookkeeping: every cell of the grid grown by one outside voxel, its case
// looked up in the table; every cut grid edge.
inline std::pair<std::size_t, std::size_t> bruteForceCounts(const Volume& v, double iso) {
    const glm::ivec3 n = v.dims() + 2;
    std::vector<unsigned char> inside(std::size_t(n.x) * n.y * n.z, 0);
    const auto at = [&](int i, int j, int k) {
        return i + std::size_t(n.x) * (j + std::size_t(n.y) * k);
    };
    for (int k = 1; k < n.z - 1; ++k) {
        for (int j = 1; j < n.y - 1; ++j) {
            for (int i = 1; i < n.x - 1; ++i) {
                inside[at(i, j, k)] = v.value(i - 1, j - 1, k - 1) >= iso;
            }
        }
    }
    std::size_t triangles = 0, vertices = 0;
    for (int k = 0; k + 1 < n.z; ++k) {
        for (int j = 0; j + 1 < n.y; ++j) {
            for (int i = 0; i + 1 < n.x; ++i) {
                int cube = 0;
                for (int c = 0; c < 8; ++c) {
                    cube |= inside[at(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1))] << c;
                }
                triangles += marchingCubesCases()[cube].triangleCount;
                // The x-, y- and z-edges from the cell's first corner.
                vertices += (cube & 1) != (cube >> 1 & 1);
                vertices += (cube & 1) != (cube >> 2 & 1);
                vertices += (cube & 1) != (cube >> 4 & 1);
            }
        }
    }
    return {triangles, vertices};
}

// The isosurface of `v` at `iso` with no other option.
inline IsosurfaceResult contour(const Volume& v, double iso) {
    IsosurfaceOptions o;
    o.iso = iso;
    return extractIsosurface(v, o);
}

} // namespace lucent::test
