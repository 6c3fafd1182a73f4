#pragma once

#include <QString>

#include "core/measure/Measurement.h"

class QPainter;

namespace lucent {

// How a measurement is drawn: the reader's own, the one picked (in a view or the
// list), one read from a foreign SR (cannot be edited), the one being drawn.
enum class MeasurementLook { Normal, Selected, ReadOnly, Draft };

// Whether m is seen on `plane`: drawn on a parallel plane and every point within
// `tolerance` mm of this one.
bool measurementInPlane(const Measurement& m, const SlicePlane& plane, double tolerance);

// The text beside a measurement: its name (if any) over its value, one value a line.
QString measurementOverlayText(const Measurement& m);

// Draws m on a view of `plane` (widget pixels = plane pixels): its lines, point
// handles and, when complete, its text. An incomplete one (being drawn) is its lines.
void paintMeasurement(QPainter& painter, const SlicePlane& plane, const Measurement& m,
                      MeasurementLook look);

// The handle radius in pixels: a press this close to a point grabs it.
constexpr double kHandleGrabPixels = 6.0;

} // namespace lucent
