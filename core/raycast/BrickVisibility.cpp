#include "core/raycast/BrickVisibility.h"

#include <cmath>
#include <limits>

namespace lucent {

std::function<bool(double, double)> valueVisibility(const RenderDescription& desc, double tableLo,
                                                    double tableHi, int tableSize) {
    const double cell = tableSize > 1 ? (tableHi - tableLo) / double(tableSize - 1) : 0.0;
    const double widen = cell + 1e-6 * (std::abs(tableLo) + std::abs(tableHi) + 1.0);
    const RenderMode mode = desc.mode;
    const double iso = desc.isoValue;
    return [mode, iso, widen, tf = desc.transferFunction](double a, double b) {
        if (mode == RenderMode::Isosurface) {
            return iso >= a - widen && iso <= b + widen;
        }
        if (mode != RenderMode::Dvr) {
            return true;
        }
        return tf.maxOpacity(a - widen, b + widen) > 0.0;
    };
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

} // namespace lucent
