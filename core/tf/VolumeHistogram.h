#pragma once

#include <cstdint>
#include <vector>

#include "core/volume/Volume.h"

namespace lucent {

// Voxel counts over equal bins of the data value, for the transfer-function
// editor's background. Bin n holds values in [lo + n w, lo + (n + 1) w) with
// w = (hi - lo) / bins; the largest value falls in the last bin.
struct VolumeHistogram {
    double lo = 0.0;
    double hi = 1.0;
    std::vector<std::uint64_t> counts;

    int binOf(double value) const;
    double binWidth() const { return counts.empty() ? 0.0 : (hi - lo) / double(counts.size()); }
    std::uint64_t largestCount() const;
};

// Counts every voxel over [min, max] of the volume (hi = lo + 1 when all voxels
// are equal). Throws std::invalid_argument for bins < 1. An empty volume gives
// all bins zero over [0, 1].
VolumeHistogram computeHistogram(const Volume& volume, int bins);

} // namespace lucent
