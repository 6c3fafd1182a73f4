#pragma once

#include <glm/glm.hpp>

#include "core/measure/Measurement.h"

namespace lucent {

// Making and reshaping measurements on the plane they are drawn on, as the reader's
// mouse does it. Points are patient LPS mm; every point made or moved here lies in
// m.plane (a point off it is projected onto it).

// A bidirectional measurement from its long axis a-b: the short axis perpendicular to
// it in the plane, through its middle, `shortRatio` times as long.
Measurement makeBidirectionalMeasurement(const SlicePlane& plane, const glm::dvec3& a,
                                         const glm::dvec3& b, double shortRatio = 0.5);

// The ellipse inscribed in the box with opposite corners a and b (box sides along
// plane.u and plane.v). Its statistics are left for the caller to take.
Measurement makeEllipseFromCorners(const SlicePlane& plane, const glm::dvec3& a,
                                   const glm::dvec3& b);

// Moves point `index` of m to `to`, keeping each kind's shape:
//   Bidirectional: a long-axis end moves freely and the short axis follows, still
//     perpendicular, crossing the long axis at the same fraction of it, its ends as far
//     from it as before; a short-axis end moves along the perpendicular only.
//   Ellipse: an axis end sets that semi-axis (the ellipse stays centred).
//   Others: the point moves.
// Returns false (m unchanged) for an index out of range.
bool moveMeasurementPoint(Measurement& m, int index, const glm::dvec3& to);

} // namespace lucent
