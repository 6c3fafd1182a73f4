// VolumeView's orientation cube: where it is and its drawing over the frame.
#include <algorithm>

#include <QPainter>

#include "ui/volume/VolumeView.h"

namespace lucent {

void VolumeView::setOrientationMarkerShown(bool shown) {
    orientationMarkerShown_ = shown;
    if (surface_) {
        surface_->update();
    }
}

OrientationCube VolumeView::orientationMarker() const {
    // The render's own camera frame: only its axes turn the cube.
    const VolumeGeometry geometry =
        volume_ && !volume_->empty() ? volume_->geometry() : VolumeGeometry{};
    const ViewFrame frame =
        makeViewFrame(geometry, camera_, std::max(1, width()), std::max(1, height()));
    return orientationCube(frame, QSizeF(size()));
}

void VolumeView::paintOrientationMarker(QPainter& painter) const {
    painter.save();
    // The device may have more pixels than the widget (high-DPI): draw in widget units.
    painter.scale(double(painter.device()->width()) / std::max(1, width()),
                  double(painter.device()->height()) / std::max(1, height()));
    paintOrientationCube(painter, orientationMarker());
    painter.restore();
}

} // namespace lucent
