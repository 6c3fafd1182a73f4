#pragma once
// Summary statistics of a per-vertex field (SVR, S, V), for reports and the
// command line's `--stats` lines.

#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace lucent {

struct FieldStats {
    std::size_t count = 0;     // finite values summarised
    std::size_t nonFinite = 0; // NaN and infinite values left out
    double mean = 0.0;
    double p05 = 0.0, p50 = 0.0, p95 = 0.0; // percentiles, linear between order statistics
    double min = 0.0, max = 0.0;
};

// All zero when no value is finite.
FieldStats fieldStats(std::span<const double> values);

// "svr_mean=0.79 svr_p05=0.65 svr_p50=... svr_p95=... svr_min=... svr_max=... svr_n=..."
// for the prefix "svr", values with 6 significant digits.
std::string statsLine(std::string_view prefix, const FieldStats& stats);

} // namespace lucent
