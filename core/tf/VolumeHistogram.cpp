#include "core/tf/VolumeHistogram.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lucent {

int VolumeHistogram::binOf(double value) const {
    const int bins = static_cast<int>(counts.size());
    if (bins == 0 || !(hi > lo)) {
        return 0;
    }
    const int bin = static_cast<int>(std::floor((value - lo) / (hi - lo) * bins));
    return std::clamp(bin, 0, bins - 1);
}

std::uint64_t VolumeHistogram::largestCount() const {
    return counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
}

VolumeHistogram computeHistogram(const Volume& volume, int bins) {
    if (bins < 1) {
        throw std::invalid_argument("histogram: at least one bin is needed");
    }
    VolumeHistogram h;
    h.counts.assign(static_cast<std::size_t>(bins), 0);
    if (volume.empty()) {
        return h;
    }
    const auto [lo, hi] = volume.valueRange();
    h.lo = lo;
    h.hi = hi > lo ? hi : lo + 1.0;
    visitVoxels(volume, [&h](auto voxels) {
        for (const auto v : voxels) {
            ++h.counts[static_cast<std::size_t>(h.binOf(static_cast<double>(v)))];
        }
    });
    return h;
}

} // namespace lucent
