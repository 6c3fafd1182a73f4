#pragma once
// The colour bar of a surface coloured by its surface-to-volume field: the
// viridis ramp (core/image/ColourMap.h) with its range and units, painted in
// a corner of the 3D view.

#include <QRectF>

class QPainter;

namespace lucent {

struct SurfaceDisplay;

// Paints the bar at the right edge of `area` when the display has a field;
// `radiusMm` goes into the caption ("SVR, R = 5 mm (1/mm)").
void paintSurfaceColourBar(QPainter& painter, const QRectF& area, const SurfaceDisplay& display,
                           double radiusMm);

} // namespace lucent
