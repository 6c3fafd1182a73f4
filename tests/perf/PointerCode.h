#pragma once
// bench_teaching's pointer positions: the k-th pointer message the presenter
// sends sits on a 1000 x 1000 raster inside the view, so that a follower can
// tell which message arrived from the position alone (each cell's centre, so
// that a server which rounds the position to 1e-4 keeps the number).

#include <cmath>
#include <utility>

namespace lucent::bench {

inline constexpr int kPointerRaster = 1000;

inline std::pair<double, double> pointerPosition(int number) {
    const double cell = 0.8 / kPointerRaster;
    return {0.1 + cell * ((number % kPointerRaster) + 0.5),
            0.1 + cell * (((number / kPointerRaster) % kPointerRaster) + 0.5)};
}

inline int pointerNumber(double x, double y) {
    const double cell = 0.8 / kPointerRaster;
    const int column = int(std::floor((x - 0.1) / cell));
    const int row = int(std::floor((y - 0.1) / cell));
    return row * kPointerRaster + column;
}

} // namespace lucent::bench
