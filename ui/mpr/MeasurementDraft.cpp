#include "ui/mpr/MeasurementDraft.h"

#include "core/measure/MeasurementGeometry.h"

namespace lucent {

namespace {

// The points the reader places: an ellipse's box corners, a bidirectional's long axis.
int placedPoints(MeasurementKind kind) {
    switch (kind) {
    case MeasurementKind::Angle:
        return 3;
    case MeasurementKind::CobbAngle:
        return 4;
    default:
        return 2;
    }
}

} // namespace

bool MeasurementDraft::startsStroke() const {
    const std::size_t n = fixed_.size();
    return n == 0 || (kind_ == MeasurementKind::CobbAngle && n == 2);
}

void MeasurementDraft::press(MeasurementKind kind, const SlicePlane& plane,
                             const glm::dvec3& point) {
    if (!active_) {
        active_ = true;
        kind_ = kind;
        plane_ = plane;
        fixed_.clear();
    }
    pressBegan_ = startsStroke();
    if (pressBegan_) {
        fixed_.push_back(point);
    }
    floating_ = point;
}

bool MeasurementDraft::release(const glm::dvec3& point, bool click) {
    if (!active_) {
        return false;
    }
    floating_ = point;
    if (click && pressBegan_) {
        return false; // the stroke's other end comes with the next click
    }
    fixed_.push_back(point);
    if (static_cast<int>(fixed_.size()) < placedPoints(kind_)) {
        return false;
    }
    active_ = false;
    // A stroke of no length measures nothing.
    return glm::distance(fixed_[0], fixed_[1]) > 0.0;
}

Measurement MeasurementDraft::preview() const {
    Measurement m;
    m.kind = kind_;
    m.plane = plane_;
    m.points = fixed_;
    if (active_ && static_cast<int>(fixed_.size()) < placedPoints(kind_)) {
        m.points.push_back(floating_);
    }
    if (static_cast<int>(m.points.size()) == placedPoints(kind_)) {
        MeasurementDraft done = *this;
        done.fixed_ = m.points;
        return done.result();
    }
    return m;
}

Measurement MeasurementDraft::result() const {
    const std::vector<glm::dvec3>& p = fixed_;
    switch (kind_) {
    case MeasurementKind::Ellipse:
        return makeEllipseFromCorners(plane_, p[0], p[1]);
    case MeasurementKind::Bidirectional:
        return makeBidirectionalMeasurement(plane_, p[0], p[1]);
    default:
        break;
    }
    Measurement m;
    m.kind = kind_;
    m.plane = plane_;
    m.points = p;
    if (kind_ == MeasurementKind::Arrow) {
        m.points = {p[1], p[0]}; // tail where the drag ended, head at the finding
    }
    return m;
}

} // namespace lucent
