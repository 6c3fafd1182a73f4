#pragma once

#include <array>
#include <vector>

#include <QColor>
#include <QRect>
#include <QStringList>

#include <glm/glm.hpp>

#include "core/mpr/PlaneSampler.h"
#include "core/volume/SeriesInfo.h"

class QPainter;

namespace lucent {

// What an MPR view draws over its image.
struct SliceOverlay {
    Orientation orientation = Orientation::Axial;
    SlicePlane plane;
    glm::dvec3 crosshair{0.0};
    // Each orientation's plane normal: the other two planes cut this one along the
    // crosshair's lines, drawn in their colours (oblique ones too).
    std::array<glm::dvec3, 3> normals{};
    QStringList topLeft;  // view name, slab, zoom
    QStringList topRight; // patient and study
    QString bottomLeft;   // slice position
    QString bottomRight;  // window
};

// Each orientation has its colour; a crosshair line shows the plane of that colour.
QColor orientationColour(Orientation orientation);

// Crosshair lines, a frame, orientation letters (A/P/R/L/S/I from the plane's axes),
// the corner texts and a scale bar.
void paintSliceOverlay(QPainter& painter, const QRect& rect, const SliceOverlay& overlay);

// A horizontal scale bar centred at the bottom of rect for pixels of pixelSize mm.
void paintScaleBar(QPainter& painter, const QRect& rect, double pixelSize);

// The curved path being clicked: its points projected on the plane, joined.
void paintCurvedPath(QPainter& painter, const SlicePlane& plane,
                     const std::vector<glm::dvec3>& points);

// The scale bar's length in mm: 1, 2 or 5 times a power of ten, the longest that
// spans at most maxPixels pixels of pixelSize mm.
double scaleBarLengthMm(double pixelSize, double maxPixels);

// Patient name, ID, study date (YYYY-MM-DD when given as YYYYMMDD), series
// description (with the modality) and, for PET, the unit of its values ("SUVbw", or
// "Bq/mL (not SUVbw)"), leaving out what is unknown.
QStringList seriesOverlayLines(const SeriesInfo& info);

} // namespace lucent
