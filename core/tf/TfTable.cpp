// The baked colour/opacity lookup table and the table lookups.
#include "core/tf/TransferFunction.h"

#include <cmath>

#include "core/tf/TableRange.h"

namespace lucent {

namespace {

// Position of `value` in a table of `size` entries over [lo, hi]: the entry below and
// the fraction towards the next, clamped to the ends (NaN reads the first entry).
struct TablePosition {
    int index = 0;
    float fraction = 0.0f;
};

TablePosition tablePosition(double value, double lo, double hi, int size) {
    if (size < 2 || !(hi > lo)) {
        return {};
    }
    const double t = (value - lo) / (hi - lo) * static_cast<double>(size - 1);
    if (!(t > 0.0)) {
        return {};
    }
    if (t >= static_cast<double>(size - 1)) {
        return {size - 2, 1.0f};
    }
    const double below = std::floor(t);
    return {static_cast<int>(below), static_cast<float>(t - below)};
}

} // namespace

void detail::checkTableRange(double lo, double hi, int size) {
    if (size < 2) {
        throw std::invalid_argument("transfer-function table: size " + std::to_string(size) +
                                    " is below 2");
    }
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
        throw std::invalid_argument("transfer-function table: the range [" + std::to_string(lo) +
                                    ", " + std::to_string(hi) + "] is empty or not finite");
    }
}

glm::vec4 TfTable::lookup(double value) const {
    const int size = static_cast<int>(rgba.size());
    if (size == 0) {
        return glm::vec4(0.0f);
    }
    if (size == 1) {
        return rgba.front();
    }
    const TablePosition p = tablePosition(value, lo, hi, size);
    const auto n = static_cast<std::size_t>(p.index);
    return glm::mix(rgba[n], rgba[n + 1], p.fraction);
}

TfTable bakeTable(const TransferFunction& tf, double lo, double hi, int size) {
    tf.validate();
    detail::checkTableRange(lo, hi, size);
    TfTable table;
    table.lo = lo;
    table.hi = hi;
    table.rgba.resize(static_cast<std::size_t>(size));
    for (int n = 0; n < size; ++n) {
        const double value = n == size - 1 ? hi : lo + n * (hi - lo) / (size - 1);
        table.rgba[static_cast<std::size_t>(n)] =
            glm::vec4(glm::dvec4(tf.colourAt(value), tf.opacityAt(value)));
    }
    return table;
}

glm::vec4 PreintegrationTable::lookup(double front, double back) const {
    if (size < 1 ||
        rgba.size() != static_cast<std::size_t>(size) * static_cast<std::size_t>(size)) {
        return glm::vec4(0.0f);
    }
    if (size == 1) {
        return rgba.front();
    }
    const TablePosition f = tablePosition(front, lo, hi, size);
    const TablePosition b = tablePosition(back, lo, hi, size);
    const auto at = [&](int i, int j) {
        return rgba[static_cast<std::size_t>(i) +
                    static_cast<std::size_t>(size) * static_cast<std::size_t>(j)];
    };
    const glm::vec4 near = glm::mix(at(f.index, b.index), at(f.index + 1, b.index), f.fraction);
    const glm::vec4 far =
        glm::mix(at(f.index, b.index + 1), at(f.index + 1, b.index + 1), f.fraction);
    return glm::mix(near, far, b.fraction);
}

} // namespace lucent
