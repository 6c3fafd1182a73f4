#pragma once

#include <optional>
#include <utility>
#include <vector>

#include <QColor>
#include <QString>

#include <glm/glm.hpp>

#include "core/mpr/PlaneSampler.h"

class QPainter;
class QRect;

namespace lucent {

// The plane another viewport shows, in the patient coordinates of the view that
// draws it: a point on it and its normal.
struct ReferencePlane {
    glm::dvec3 point{0.0};
    glm::dvec3 normal{0.0, 0.0, 1.0};
    QColor colour;
    QString label; // short: the other viewport's number
};

// The line where `other` cuts `plane`, as two pixel positions of `plane` far
// outside any widget, or nothing when the planes are (nearly) parallel.
std::optional<std::pair<glm::dvec2, glm::dvec2>> referenceLine(const SlicePlane& plane,
                                                               const ReferencePlane& other);

// Each reference plane's line across rect, dashed in its colour, labelled at its end.
void paintReferenceLines(QPainter& painter, const QRect& rect, const SlicePlane& plane,
                         const std::vector<ReferencePlane>& others);

} // namespace lucent
