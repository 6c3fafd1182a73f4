#include "core/mpr/RoiStatistics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lucent {

RoiStatistics ellipseStatistics(const Volume& volume, const SlicePlane& plane,
                                const EllipseRoi& ellipse, double spacing) {
    RoiStatistics stats;
    if (!(ellipse.radiusU > 0.0) || !(ellipse.radiusV > 0.0)) {
        return stats;
    }
    stats.areaMm2 = std::numbers::pi * ellipse.radiusU * ellipse.radiusV;
    const double step = spacing > 0.0 ? spacing : plane.pixelSize;
    if (!(step > 0.0)) {
        return stats;
    }
    // A lattice of odd size, its middle point on the ellipse's centre.
    const int halfU = static_cast<int>(std::floor(ellipse.radiusU / step));
    const int halfV = static_cast<int>(std::floor(ellipse.radiusV / step));
    SlicePlane lattice = plane;
    lattice.centre = ellipse.centre - plane.normal() * plane.distance(ellipse.centre);
    lattice.pixelSize = step;
    lattice.width = 2 * halfU + 1;
    lattice.height = 2 * halfV + 1;
    const std::vector<float> values = sampleImage(volume, lattice);

    // Welford's running mean and variance.
    double mean = 0.0;
    double m2 = 0.0;
    std::size_t n = 0;
    for (int y = 0; y < lattice.height; ++y) {
        const double dv = (y - halfV) * step / ellipse.radiusV;
        for (int x = 0; x < lattice.width; ++x) {
            const double du = (x - halfU) * step / ellipse.radiusU;
            if (du * du + dv * dv > 1.0 + 1e-12) {
                continue;
            }
            const double value =
                values[static_cast<std::size_t>(y) * static_cast<std::size_t>(lattice.width) +
                       static_cast<std::size_t>(x)];
            if (std::isnan(value)) {
                continue;
            }
            ++n;
            const double delta = value - mean;
            mean += delta / static_cast<double>(n);
            m2 += delta * (value - mean);
            stats.minimum = n == 1 ? value : std::min(stats.minimum, value);
            stats.maximum = n == 1 ? value : std::max(stats.maximum, value);
        }
    }
    stats.samples = n;
    if (n > 0) {
        stats.mean = mean;
        stats.standardDeviation = std::sqrt(std::max(0.0, m2 / static_cast<double>(n)));
    }
    return stats;
}

} // namespace lucent
