#include "core/surface/FieldStats.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <utility>
#include <vector>

namespace lucent {

namespace {

// Percentile q (0..1) of sorted values, linear between neighbours (NumPy's default).
double percentile(const std::vector<double>& sorted, double q) {
    const double position = q * double(sorted.size() - 1);
    const std::size_t below = std::size_t(std::floor(position));
    const std::size_t above = std::min(below + 1, sorted.size() - 1);
    const double t = position - double(below);
    return sorted[below] + t * (sorted[above] - sorted[below]);
}

} // namespace

FieldStats fieldStats(std::span<const double> values) {
    std::vector<double> finite;
    finite.reserve(values.size());
    std::copy_if(values.begin(), values.end(), std::back_inserter(finite),
                 [](double v) { return std::isfinite(v); });
    FieldStats stats;
    stats.nonFinite = values.size() - finite.size();
    stats.count = finite.size();
    if (finite.empty()) {
        return stats;
    }
    std::sort(finite.begin(), finite.end());
    double sum = 0.0;
    for (const double v : finite) {
        sum += v;
    }
    stats.mean = sum / double(finite.size());
    stats.p05 = percentile(finite, 0.05);
    stats.p50 = percentile(finite, 0.50);
    stats.p95 = percentile(finite, 0.95);
    stats.min = finite.front();
    stats.max = finite.back();
    return stats;
}

std::string statsLine(std::string_view prefix, const FieldStats& stats) {
    std::ostringstream line;
    line.precision(6);
    const std::pair<const char*, double> items[] = {{"mean", stats.mean}, {"p05", stats.p05},
                                                    {"p50", stats.p50},   {"p95", stats.p95},
                                                    {"min", stats.min},   {"max", stats.max}};
    for (const auto& [name, value] : items) {
        line << prefix << '_' << name << '=' << value << ' ';
    }
    line << prefix << "_n=" << stats.count;
    return line.str();
}

} // namespace lucent
