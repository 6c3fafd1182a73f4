#include "core/pet/SuvStatistics.h"

#include <cmath>
#include <numbers>

namespace lucent {

namespace {

bool inside(const glm::ivec3& dims, const glm::ivec3& v) {
    return v.x >= 0 && v.y >= 0 && v.z >= 0 && v.x < dims.x && v.y < dims.y && v.z < dims.z;
}

// Index offsets whose voxel centres lie within radiusMm of the centre voxel's.
std::vector<glm::ivec3> sphereOffsets(const glm::dvec3& spacing, double radiusMm) {
    const glm::ivec3 reach(glm::floor(glm::dvec3(radiusMm) / spacing));
    const double limit = radiusMm * radiusMm * (1.0 + 1e-12);
    std::vector<glm::ivec3> offsets;
    for (int k = -reach.z; k <= reach.z; ++k) {
        for (int j = -reach.y; j <= reach.y; ++j) {
            for (int i = -reach.x; i <= reach.x; ++i) {
                const glm::dvec3 d = glm::dvec3(i, j, k) * spacing;
                if (glm::dot(d, d) <= limit) {
                    offsets.emplace_back(i, j, k);
                }
            }
        }
    }
    return offsets;
}

double offsetsMean(const Volume& volume, const glm::ivec3& centre,
                   const std::vector<glm::ivec3>& offsets) {
    if (!inside(volume.dims(), centre)) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    double sum = 0.0;
    std::size_t count = 0;
    for (const glm::ivec3& o : offsets) {
        const glm::ivec3 v = centre + o;
        if (inside(volume.dims(), v)) {
            sum += volume.value(v.x, v.y, v.z);
            ++count;
        }
    }
    return sum / static_cast<double>(count);
}

} // namespace

double suvPeakRadiusMm() {
    return 10.0 * std::cbrt(3.0 / (4.0 * std::numbers::pi));
}

Volume suvVolume(const Volume& activity, double factor) {
    Volume suv(activity.geometry(), VoxelType::Float32);
    static_cast<SeriesInfo&>(suv) = static_cast<const SeriesInfo&>(activity);
    suv.warnings = activity.warnings;
    const std::span<float> out = suv.voxels<float>();
    visitVoxels(activity, [&](auto in) {
        for (std::size_t n = 0; n < in.size(); ++n) {
            out[n] = static_cast<float>(static_cast<double>(in[n]) * factor);
        }
    });
    return suv;
}

std::vector<glm::ivec3> ellipsoidVoxels(const VolumeGeometry& geometry, const glm::dvec3& centre,
                                        const glm::dvec3& radiiMm) {
    std::vector<glm::ivec3> voxels;
    if (!(radiiMm.x > 0.0 && radiiMm.y > 0.0 && radiiMm.z > 0.0)) {
        return voxels;
    }
    const glm::dvec3 c = geometry.toIndex(centre);
    const glm::dvec3 reach = radiiMm / geometry.spacing;
    const glm::ivec3 lo = glm::max(glm::ivec3(glm::ceil(c - reach)), glm::ivec3(0));
    const glm::ivec3 hi = glm::min(glm::ivec3(glm::floor(c + reach)), geometry.dims - 1);
    for (int k = lo.z; k <= hi.z; ++k) {
        for (int j = lo.y; j <= hi.y; ++j) {
            for (int i = lo.x; i <= hi.x; ++i) {
                const glm::dvec3 q = (glm::dvec3(i, j, k) - c) / reach;
                if (glm::dot(q, q) <= 1.0 + 1e-12) {
                    voxels.emplace_back(i, j, k);
                }
            }
        }
    }
    return voxels;
}

double sphereMean(const Volume& volume, const glm::ivec3& centre, double radiusMm) {
    return offsetsMean(volume, centre, sphereOffsets(volume.geometry().spacing, radiusMm));
}

SuvStatistics suvStatistics(const Volume& suv, std::span<const glm::ivec3> region) {
    SuvStatistics s;
    const std::vector<glm::ivec3> offsets =
        sphereOffsets(suv.geometry().spacing, suvPeakRadiusMm());
    double sum = 0.0;
    for (const glm::ivec3& v : region) {
        if (!inside(suv.dims(), v)) {
            continue;
        }
        const double value = suv.value(v.x, v.y, v.z);
        sum += value;
        if (s.voxels++ == 0 || value > s.max) {
            s.max = value;
            s.maxVoxel = v;
        }
        const double peak = offsetsMean(suv, v, offsets);
        if (s.voxels == 1 || peak > s.peak) {
            s.peak = peak;
            s.peakVoxel = v;
        }
    }
    if (s.voxels > 0) {
        s.mean = sum / static_cast<double>(s.voxels);
    }
    return s;
}

} // namespace lucent
