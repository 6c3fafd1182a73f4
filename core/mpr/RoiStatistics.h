#pragma once

#include <cstddef>
#include <limits>

#include <glm/glm.hpp>

#include "core/mpr/PlaneSampler.h"
#include "core/volume/Volume.h"

namespace lucent {

// Statistics of the values inside a region of a resliced plane.
struct RoiStatistics {
    double mean = std::numeric_limits<double>::quiet_NaN();
    double standardDeviation = std::numeric_limits<double>::quiet_NaN(); // population SD
    double minimum = std::numeric_limits<double>::quiet_NaN();
    double maximum = std::numeric_limits<double>::quiet_NaN();
    double areaMm2 = 0.0;    // the region's area (the ellipse's, pi * a * b)
    std::size_t samples = 0; // samples inside the region and inside the volume
};

// An ellipse in the plane: centred at `centre` (projected onto the plane), with
// semi-axes radiusU along plane.u and radiusV along plane.v, in mm.
struct EllipseRoi {
    glm::dvec3 centre{0.0};
    double radiusU = 0.0;
    double radiusV = 0.0;
};

// Samples the plane (its slab settings included, as sampleImage does) on a square
// lattice of `spacing` mm centred on the ellipse, and takes the samples whose
// lattice points lie inside the ellipse (boundary included) and inside the volume.
// A spacing <= 0 means the plane's pixel size. An ellipse with a radius <= 0 has
// no samples and no area.
RoiStatistics ellipseStatistics(const Volume& volume, const SlicePlane& plane,
                                const EllipseRoi& ellipse, double spacing = 0.0);

} // namespace lucent
