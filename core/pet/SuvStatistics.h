#pragma once
// Region statistics on a volume of SUV values: SUVmax, SUVmean and SUVpeak (the highest
// mean over a 1 mL sphere), as PERCIST reads them. Plain C++ (lucent_core).

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/mpr/RoiStatistics.h"
#include "core/pet/SuvParameters.h"
#include "core/volume/Volume.h"

namespace lucent {

// The radius of a 1 mL sphere: (3 / (4 pi))^(1/3) cm, about 6.2035 mm.
double suvPeakRadiusMm();

// A copy of `activity` (Bq/mL, rescale applied) as Float32 SUV values: each voxel times
// `factor` (suvBwFactor). Geometry and series description are kept.
Volume suvVolume(const Volume& activity, double factor);

// A PET volume as the workstation shows it: in SUVbw (suvVolume with petDisplayOf's factor;
// Units GML as stored) when a factor can be had, else as stored; its `pet` says which, and
// why not.
Volume petVolumeForDisplay(Volume stored, const SuvParameters& parameters);

// The voxels whose centres lie inside an ellipsoid: centred at `centre` (LPS mm), with
// semi-axes `radiiMm` along the volume's i, j and k axes (boundary included).
std::vector<glm::ivec3> ellipsoidVoxels(const VolumeGeometry& geometry, const glm::dvec3& centre,
                                        const glm::dvec3& radiiMm);
// The same for an ellipsoid of any orientation: semi-axis n is radiiMm[n] along the unit
// vector axes[n] (LPS; the columns of `axes`, orthogonal).
std::vector<glm::ivec3> ellipsoidVoxels(const VolumeGeometry& geometry, const glm::dvec3& centre,
                                        const glm::dmat3& axes, const glm::dvec3& radiiMm);

// The region an ellipse ROI drawn on `plane` gives PET reading: the ellipsoid it spans, its
// semi-axes the ellipse's along plane.u and plane.v and the shorter of the two along the
// plane's normal. PERCIST reads SUVmax and SUVpeak per lesion in 3D, so the hottest voxel
// and the hottest 1 mL sphere may lie on a neighbouring slice of the one drawn on; the
// shorter axis keeps the region from reaching further along the normal than across.
std::vector<glm::ivec3> ellipseSuvRegion(const VolumeGeometry& geometry, const SlicePlane& plane,
                                         const EllipseRoi& ellipse);

struct SuvStatistics {
    double max = std::numeric_limits<double>::quiet_NaN();
    double mean = std::numeric_limits<double>::quiet_NaN();
    double peak = std::numeric_limits<double>::quiet_NaN();
    glm::ivec3 maxVoxel{-1};  // where max is (the first such voxel of the region)
    glm::ivec3 peakVoxel{-1}; // the centre of the sphere whose mean is peak
    std::size_t voxels = 0;   // region voxels inside the volume
};

// The mean of the voxels whose centres lie within radiusMm of voxel `centre` (distances
// from the voxel spacing), over the voxels inside the volume. NaN when centre is outside.
double sphereMean(const Volume& volume, const glm::ivec3& centre, double radiusMm);

// SUVmax and SUVmean over `region` (voxel indices; those outside the volume are ignored, one
// listed twice counts twice) and SUVpeak: the highest sphereMean(suvPeakRadiusMm())
// centred on a voxel of the region. The sphere takes every voxel of the volume inside it,
// inside the region or not. All NaN for an empty region.
SuvStatistics suvStatistics(const Volume& suv, std::span<const glm::ivec3> region);

} // namespace lucent
