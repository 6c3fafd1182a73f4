#include "core/pet/SuvStatistics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/pet/PetDisplay.h"

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

Volume petVolumeForDisplay(Volume stored, const SuvParameters& parameters) {
    const PetDisplay display = petDisplayOf(parameters);
    Volume shown = display.inSuv() && display.suvFactor != 1.0
                       ? suvVolume(stored, display.suvFactor)
                       : std::move(stored);
    shown.pet = display;
    return shown;
}

std::vector<glm::ivec3> ellipsoidVoxels(const VolumeGeometry& geometry, const glm::dvec3& centre,
                                        const glm::dmat3& axes, const glm::dvec3& radiiMm) {
    std::vector<glm::ivec3> voxels;
    if (!(radiiMm.x > 0.0 && radiiMm.y > 0.0 && radiiMm.z > 0.0)) {
        return voxels;
    }
    // Index offsets per mm along each patient direction: the rows of the inverse of
    // direction * diag(spacing). The box reaches sqrt(sum_n (r_n * row . axis_n)^2) along
    // each index axis.
    const glm::dmat3 toIndex = glm::inverse(
        geometry.direction *
        glm::dmat3(geometry.spacing.x, 0, 0, 0, geometry.spacing.y, 0, 0, 0, geometry.spacing.z));
    const glm::dvec3 c = geometry.toIndex(centre);
    glm::dvec3 reach(0.0);
    for (int a = 0; a < 3; ++a) {
        const glm::dvec3 row(toIndex[0][a], toIndex[1][a], toIndex[2][a]);
        for (int n = 0; n < 3; ++n) {
            const double d = radiiMm[n] * glm::dot(row, axes[n]);
            reach[a] += d * d;
        }
        reach[a] = std::sqrt(reach[a]);
    }
    const glm::ivec3 lo = glm::max(glm::ivec3(glm::ceil(c - reach - 1e-9)), glm::ivec3(0));
    const glm::ivec3 hi = glm::min(glm::ivec3(glm::floor(c + reach + 1e-9)), geometry.dims - 1);
    for (int k = lo.z; k <= hi.z; ++k) {
        for (int j = lo.y; j <= hi.y; ++j) {
            for (int i = lo.x; i <= hi.x; ++i) {
                const glm::dvec3 d = geometry.toPatient(glm::dvec3(i, j, k)) - centre;
                const glm::dvec3 q(glm::dot(d, axes[0]) / radiiMm.x,
                                   glm::dot(d, axes[1]) / radiiMm.y,
                                   glm::dot(d, axes[2]) / radiiMm.z);
                if (glm::dot(q, q) <= 1.0 + 1e-12) {
                    voxels.emplace_back(i, j, k);
                }
            }
        }
    }
    return voxels;
}

std::vector<glm::ivec3> ellipseSuvRegion(const VolumeGeometry& geometry, const SlicePlane& plane,
                                         const EllipseRoi& ellipse) {
    const glm::dvec3 u = glm::normalize(plane.u);
    const glm::dvec3 v = glm::normalize(plane.v);
    const glm::dvec3 n = glm::normalize(glm::cross(u, v));
    const glm::dvec3 centre = ellipse.centre - n * glm::dot(ellipse.centre - plane.centre, n);
    const double across = std::min(ellipse.radiusU, ellipse.radiusV);
    return ellipsoidVoxels(geometry, centre, glm::dmat3(u, v, n),
                           glm::dvec3(ellipse.radiusU, ellipse.radiusV, across));
}

std::vector<glm::ivec3> ellipsoidVoxels(const VolumeGeometry& geometry, const glm::dvec3& centre,
                                        const glm::dvec3& radiiMm) {
    return ellipsoidVoxels(geometry, centre, geometry.direction, radiiMm);
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
