#pragma once
// A vertical colour bar of an overlay's map over its window: the high end at the top,
// the window's ends and middle written beside it with the unit.

#include <QString>

#include "core/fusion/FusionStyle.h"

class QPainter;
class QRect;

namespace lucent {

// Drawn inside `area` (its right part holds the bar, the labels go left of it).
void paintFusionColourBar(QPainter& painter, const QRect& area, const FusionStyle& style,
                          const QString& unit);

// "2.5", "-1000", "0.004": a window value as the bar labels it (4 significant digits).
QString colourBarLabel(double value);

} // namespace lucent
