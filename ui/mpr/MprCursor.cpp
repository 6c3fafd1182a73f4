#include "ui/mpr/MprCursor.h"

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

void MprCursor::setInvertedGrey(bool inverted) {
    if (inverted == invertedGrey_) {
        return;
    }
    invertedGrey_ = inverted;
    emit windowChanged();
}

const glm::dmat3& MprCursor::rotation(Orientation orientation) const {
    return rotations_[static_cast<std::size_t>(orientation)];
}

void MprCursor::setRotation(Orientation orientation, const glm::dmat3& rotation) {
    glm::dmat3& r = rotations_[static_cast<std::size_t>(orientation)];
    if (r == rotation) {
        return;
    }
    r = rotation;
    emit rotationChanged();
}

void MprCursor::resetRotations() {
    for (const Orientation o : {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
        setRotation(o, glm::dmat3(1.0));
    }
}

glm::dvec3 MprCursor::planeU(Orientation orientation) const {
    return rotation(orientation) * standardPlane({}, orientation, point_).u;
}

glm::dvec3 MprCursor::planeV(Orientation orientation) const {
    return rotation(orientation) * standardPlane({}, orientation, point_).v;
}

glm::dvec3 MprCursor::planeNormal(Orientation orientation) const {
    return glm::cross(planeU(orientation), planeV(orientation));
}

void centreOn(MprCursor& cursor, const Volume& volume) {
    if (volume.empty()) {
        return;
    }
    cursor.resetRotations();
    cursor.setPoint(volume.geometry().toPatient(glm::dvec3(volume.dims() / 2)));
    const WindowLevel window = defaultWindow(volume);
    cursor.setWindowStep(window.step);
    cursor.setWindow(window.center, window.width);
    cursor.setInvertedGrey(volume.modality == "PT");
}

} // namespace lucent
