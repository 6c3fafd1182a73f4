#pragma once
// An MPR view samples its slice at device pixels: on a screen with a device pixel
// ratio of 2 the image has twice the logical width and height, and is drawn with
// QImage::setDevicePixelRatio so that the overlays, measurements and mouse stay in
// logical (widget) coordinates, as SliceView::plane() describes them.

#include <QPointF>

#include "core/mpr/PlaneSampler.h"

namespace lucent {

// The plane of `logical` (widget pixels) sampled at `ratio` device pixels per
// widget pixel: ceil(width * ratio) by ceil(height * ratio) pixels of
// pixelSize / ratio, device pixel (i, j) at the logical position (i / ratio,
// j / ratio), as a logical pixel takes the value at its own position. A ratio
// of 1 (or less) gives `logical` back unchanged.
SlicePlane devicePlane(const SlicePlane& logical, double ratio);

// The device pixel holding widget position `pos` (the one whose area, from
// its position to the next, contains it) for a device plane of `ratio`.
QPoint devicePixelAt(const QPointF& pos, double ratio);

} // namespace lucent
