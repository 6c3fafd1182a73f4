#include "ui/MprCursor.h"

#include <algorithm>

namespace lucent {

MprCursor::MprCursor(QObject* parent) : QObject(parent) {}

void MprCursor::setPoint(const glm::dvec3& point) {
    if (point == point_) {
        return;
    }
    point_ = point;
    emit pointChanged();
}

void MprCursor::setWindow(double center, double width) {
    width = std::max(width, windowStep_);
    if (center == center_ && width == width_) {
        return;
    }
    center_ = center;
    width_ = width;
    emit windowChanged();
}

} // namespace lucent
