#pragma once
// What the render benchmarks share: the VTK anchor's opacity unit and the median.

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/tf/TransferFunction.h"
#include "core/volume/Volume.h"

namespace lucent::bench {

// A transfer function whose opacities are per unitMm (VTK's unit distance is
// 1 mm) rewritten per dt_ref, Lucent's unit: a' = 1 - (1 - a)^(dt_ref / unit).
// unitMm <= 0 leaves it as it is.
inline TransferFunction opacityPerUnit(TransferFunction tf, const Volume& volume, double unitMm) {
    if (unitMm > 0.0) {
        const glm::dvec3 s = volume.geometry().spacing;
        const double ratio = std::min({s.x, s.y, s.z}) / unitMm;
        for (OpacityPoint& p : tf.opacity) {
            p.opacity = 1.0 - std::pow(1.0 - p.opacity, ratio);
        }
    }
    return tf;
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

} // namespace lucent::bench
