// The cells of lucent-cli bench interactive's table (InteractiveRows.h).
#include <cstdio>

#include "InteractiveRows.h"
#include "app/bench/VtkAnchor.h"
#include "render/OffscreenContext.h"

namespace lucent::cli {

namespace {

std::string formatted(const char* format, double v) {
    char text[64];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

} // namespace

InteractiveDevices::InteractiveDevices() = default;
InteractiveDevices::~InteractiveDevices() = default;
InteractiveDevices::InteractiveDevices(InteractiveDevices&&) noexcept = default;

std::string unitName(double unitMm) {
    if (unitMm <= 0.0) {
        return "opacity per voxel";
    }
    return unitMm == 1.0 ? "opacity per mm" : formatted("opacity per %g mm", unitMm);
}

std::string msCell(double ms) {
    // Three significant figures or more: 0.504 ms must not read as 0.50 beside a 0.5 ms goal.
    return formatted(ms >= 100.0  ? "%.0f ms"
                     : ms >= 10.0 ? "%.1f ms"
                     : ms >= 1.0  ? "%.2f ms"
                                  : "%.3f ms",
                     ms);
}

std::string dbCell(double db) {
    return formatted("%.1f dB", db);
}

std::string ratioCell(double ratio) {
    return formatted("%.3f", ratio);
}

std::string metCell(bool met) {
    return met ? "yes" : "no";
}

InteractiveRow missingRow(std::string what, std::string goal, const std::string& why) {
    InteractiveRow row;
    row.what = std::move(what);
    row.lucent = why;
    row.goal = std::move(goal);
    return row;
}

InteractiveRow goalRow(std::string what, std::string lucent, std::string goal, bool met) {
    InteractiveRow row = missingRow(std::move(what), std::move(goal), lucent);
    row.met = metCell(met);
    return row;
}

} // namespace lucent::cli
