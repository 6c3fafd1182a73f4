#include "ui/mpr/DevicePlane.h"

#include <cmath>

namespace lucent {

namespace {

// Whole device pixels covering `logical` widget pixels; a hair of slack so that
// 100 * 1.1 (110.00000000000001) stays 110.
int devicePixels(int logical, double ratio) {
    return static_cast<int>(std::ceil(logical * ratio - 1e-6));
}

} // namespace

SlicePlane devicePlane(const SlicePlane& logical, double ratio) {
    if (ratio <= 1.0) {
        return logical;
    }
    SlicePlane device = logical;
    device.width = devicePixels(logical.width, ratio);
    device.height = devicePixels(logical.height, ratio);
    device.pixelSize = logical.pixelSize / ratio;
    // Device pixel (0, 0) lies where logical pixel (0, 0) does; the centre is
    // half the device image away from it.
    device.centre = logical.pointAt(0.0, 0.0) +
                    device.u * (0.5 * (device.width - 1) * device.pixelSize) +
                    device.v * (0.5 * (device.height - 1) * device.pixelSize);
    return device;
}

QPoint devicePixelAt(const QPointF& pos, double ratio) {
    const double r = ratio > 1.0 ? ratio : 1.0;
    return {static_cast<int>(std::floor(pos.x() * r)), static_cast<int>(std::floor(pos.y() * r))};
}

} // namespace lucent
