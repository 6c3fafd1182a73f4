#include "core/raycast/BrickVisibility.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lucent {

VisibilityKey visibilityKey(const RenderDescription& desc, double tableLo, double tableHi,
                            int tableSize) {
    const double cell = tableSize > 1 ? (tableHi - tableLo) / double(tableSize - 1) : 0.0;
    VisibilityKey key;
    key.mode = desc.mode;
    key.widen = cell + 1e-6 * (std::abs(tableLo) + std::abs(tableHi) + 1.0);
    if (desc.mode == RenderMode::Isosurface) {
        key.isoValue = desc.isoValue;
    }
    if (desc.mode == RenderMode::Dvr) {
        key.opacity = desc.transferFunction.opacity;
    }
    return key;
}

std::function<bool(double, double)> valueVisibility(const VisibilityKey& key) {
    TransferFunction opacity;
    opacity.opacity = key.opacity;
    return [mode = key.mode, iso = key.isoValue, widen = key.widen,
            tf = std::move(opacity)](double a, double b) {
        if (mode == RenderMode::Isosurface) {
            return iso >= a - widen && iso <= b + widen;
        }
        if (mode != RenderMode::Dvr) {
            return true;
        }
        return tf.maxOpacity(a - widen, b + widen) > 0.0;
    };
}

std::function<bool(double, double)> valueVisibility(const RenderDescription& desc, double tableLo,
                                                    double tableHi, int tableSize) {
    return valueVisibility(visibilityKey(desc, tableLo, tableHi, tableSize));
}

std::pair<double, double> tableRange(double lo, double hi) {
    if (hi > lo) {
        return {lo, hi};
    }
    return {lo, lo + std::max(1.0, std::abs(lo) * 1e-6)};
}

double gradientScale(double valueLo, double valueHi) {
    const double m = std::max(std::abs(valueLo), std::abs(valueHi));
    return m > 0.0 && std::isfinite(m) ? m : 1.0;
}

std::pair<double, double> visibleValueRange(const TransferFunction& tf, double tableCell) {
    const auto& op = tf.opacity;
    const double inf = std::numeric_limits<double>::infinity();
    double lo = -inf, hi = inf;
    if (!op.empty() && op.front().opacity <= 0.0) {
        std::size_t i = 0;
        while (i + 1 < op.size() && op[i + 1].opacity <= 0.0) {
            ++i;
        }
        lo = i + 1 < op.size() ? op[i].value : inf;
    }
    if (!op.empty() && op.back().opacity <= 0.0) {
        std::size_t i = op.size() - 1;
        while (i > 0 && op[i - 1].opacity <= 0.0) {
            --i;
        }
        hi = i > 0 ? op[i].value : -inf;
    }
    return {lo - tableCell, hi + tableCell};
}

bool boxInView(const VolumeGeometry& g, const ViewFrame& f, const glm::dvec3& lo,
               const glm::dvec3& hi) {
    // Per side of the view: how many corners lie beyond it.
    int left = 0, right = 0, below = 0, above = 0, behind = 0;
    const double tx = f.tanHalfFov * f.aspect, ty = f.tanHalfFov;
    for (int n = 0; n < 8; ++n) {
        const glm::dvec3 c((n & 1) ? hi.x : lo.x, (n & 2) ? hi.y : lo.y, (n & 4) ? hi.z : lo.z);
        const glm::dvec3 rel = g.toPatient(c) - f.eye;
        const double z = glm::dot(rel, f.forward);
        if (z <= 0.0) {
            ++behind;
            continue;
        }
        const double x = glm::dot(rel, f.right) / (z * tx), y = glm::dot(rel, f.up) / (z * ty);
        left += x < -1.0;
        right += x > 1.0;
        below += y < -1.0;
        above += y > 1.0;
    }
    if (behind == 8) {
        return false;
    }
    if (behind > 0) {
        return true; // the box reaches behind the eye: keep it
    }
    return left < 8 && right < 8 && below < 8 && above < 8;
}

} // namespace lucent
