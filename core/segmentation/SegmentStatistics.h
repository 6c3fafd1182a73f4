#pragma once
// What the Segments panel, its CSV and lucent-cli segment-stats report of a segment.

#include <cstddef>
#include <limits>

#include "core/segmentation/SegmentMask.h"
#include "core/volume/Volume.h"

namespace lucent {

struct SegmentStatistics {
    static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    std::size_t voxels = 0;
    double volumeMl = 0.0;            // voxels x the voxel volume, mm^3 / 1000
    double mean = kNone;              // of the volume's values (HU for CT) in the segment
    double standardDeviation = kNone; // population
    double minimum = kNone;
    double maximum = kNone;
    double median = kNone; // the lower median of an even count
    // The closed surface (marching cubes of the mask, Gaussian sigma 1 voxel as Slicer's
    // closed surface smooths it), cm^2.
    double surfaceAreaCm2 = kNone;
    // The largest distance between two voxel centres of the segment, mm (its Feret
    // diameter on the voxel centres).
    double largestDiameterMm = kNone;
};

// `volume` gives the values and the grid (the mask's dims must be its dims:
// std::invalid_argument otherwise). An empty mask has 0 voxels and NaN elsewhere.
SegmentStatistics segmentStatistics(const SegmentMask& mask, const Volume& volume);

// The largest distance between two voxel centres of the mask, mm (0 for one voxel, NaN
// for none). Exact: the farthest pair are vertices of the convex hull, and every vertex of
// the 3D hull is a vertex of its slice's 2D hull (of the row ends), so those candidates are
// measured pairwise.
double largestDiameterMm(const SegmentMask& mask, const VolumeGeometry& grid);

} // namespace lucent
