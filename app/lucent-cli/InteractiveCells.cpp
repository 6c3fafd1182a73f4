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
    return formatted(ms >= 100.0 ? "%.0f ms" : ms >= 10.0 ? "%.1f ms" : "%.2f ms", ms);
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

} // namespace lucent::cli
