#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/measure/Measurement.h"

namespace lucent {

// The measurement being drawn with the mouse, in strokes: a stroke of two points is a
// drag (press at one end, release at the other) or two clicks; a stroke of one point
// is a click. Distance, arrow, bidirectional (its long axis) and ellipse (its box) are
// one stroke of two points; an angle is a stroke of two (arm end, vertex) and one of
// one (the other arm's end); a Cobb angle two strokes of two (its lines).
// Between clicks the open point follows the mouse (hover).
class MeasurementDraft {
public:
    bool active() const { return active_; }
    MeasurementKind kind() const { return kind_; }

    // A press at `point` (in `plane`); the first one starts a draft of `kind`.
    void press(MeasurementKind kind, const SlicePlane& plane, const glm::dvec3& point);
    void hover(const glm::dvec3& point) { floating_ = point; }
    // A release at `point`: `click` when the mouse did not move from the press.
    // Returns true when the last point is in: result() is the measurement.
    bool release(const glm::dvec3& point, bool click);
    void cancel() { active_ = false; }

    // The points so far and the one following the mouse, for drawing.
    Measurement preview() const;
    // The finished measurement (an arrow's head is where the drag began).
    Measurement result() const;

private:
    bool startsStroke() const; // the next press begins a stroke of two points

    bool active_ = false;
    bool pressBegan_ = false; // the last press began a stroke
    MeasurementKind kind_ = MeasurementKind::Distance;
    SlicePlane plane_;
    std::vector<glm::dvec3> fixed_;
    glm::dvec3 floating_{0.0};
};

} // namespace lucent
