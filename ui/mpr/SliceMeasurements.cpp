#include "ui/mpr/SliceMeasurements.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <QPainter>

namespace lucent {

namespace {

const QColor kMeasureColour(255, 230, 80);

bool inPlane(const SlicePlane& drawnOn, const glm::dvec3& point, const SlicePlane& plane,
             double tolerance) {
    return std::abs(glm::dot(drawnOn.normal(), plane.normal())) > 0.9999 &&
           std::abs(plane.distance(point)) <= tolerance;
}

QPointF toWidget(const SlicePlane& plane, const glm::dvec3& p) {
    const glm::dvec2 px = plane.pixelOf(p);
    return {px.x + 0.5, px.y + 0.5};
}

void paintLabel(QPainter& painter, const QPointF& at, const QString& text) {
    const QRectF box =
        painter.fontMetrics().boundingRect(QRect(0, 0, 400, 100), Qt::AlignLeft, text);
    QRectF placed = box.translated(at + QPointF(6.0, 6.0)).adjusted(-2, -1, 2, 1);
    // Kept inside the view: moved left or up where it would leave it.
    const QRectF view = painter.window();
    placed.moveLeft(std::max(view.left(), std::min(placed.left(), view.right() - placed.width())));
    placed.moveTop(std::max(view.top(), std::min(placed.top(), view.bottom() - placed.height())));
    painter.fillRect(placed, QColor(0, 0, 0, 150));
    painter.drawText(placed, Qt::AlignCenter, text);
}

void paintEllipse(QPainter& painter, const SlicePlane& plane, const SlicePlane& drawnOn,
                  const EllipseRoi& e) {
    const QPointF c = toWidget(plane, e.centre);
    const double angle = std::atan2(glm::dot(drawnOn.u, plane.v), glm::dot(drawnOn.u, plane.u));
    painter.save();
    painter.translate(c);
    painter.rotate(angle * 180.0 / std::numbers::pi);
    const double ru = e.radiusU / plane.pixelSize;
    const double rv = e.radiusV / plane.pixelSize;
    painter.drawEllipse(QPointF(0.0, 0.0), ru, rv);
    painter.restore();
}

} // namespace

void SliceMeasurements::begin(MeasurementKind kind, const glm::dvec3& point) {
    drawing_ = true;
    kind_ = kind;
    first_ = point;
    current_ = point;
}

void SliceMeasurements::moveTo(const glm::dvec3& point) {
    current_ = point;
}

EllipseRoi SliceMeasurements::ellipseBetween(const glm::dvec3& a, const glm::dvec3& b,
                                             const SlicePlane& plane) {
    EllipseRoi e;
    e.centre = 0.5 * (a + b);
    e.radiusU = 0.5 * std::abs(glm::dot(b - a, plane.u));
    e.radiusV = 0.5 * std::abs(glm::dot(b - a, plane.v));
    return e;
}

void SliceMeasurements::finish(const glm::dvec3& point, const Volume& volume,
                               const SlicePlane& plane) {
    if (!drawing_) {
        return;
    }
    drawing_ = false;
    if (kind_ == MeasurementKind::Distance) {
        distances_.push_back({first_, point});
        return;
    }
    EllipseMeasurement m;
    m.plane = plane;
    m.ellipse = ellipseBetween(first_, point, plane);
    // At least two samples per voxel across, whatever the zoom.
    const glm::dvec3 s = volume.geometry().spacing;
    const double spacing = std::min(plane.pixelSize, 0.5 * std::min({s.x, s.y, s.z}));
    m.statistics = ellipseStatistics(volume, plane, m.ellipse, spacing);
    ellipses_.push_back(m);
}

void SliceMeasurements::clear() {
    drawing_ = false;
    distances_.clear();
    ellipses_.clear();
}

void SliceMeasurements::paint(QPainter& painter, const SlicePlane& plane, double tolerance,
                              const QString& unit) const {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(kMeasureColour, 1.5));
    painter.setBrush(Qt::NoBrush);
    auto paintDistance = [&](const DistanceMeasurement& d) {
        const QPointF a = toWidget(plane, d.start);
        const QPointF b = toWidget(plane, d.end);
        painter.drawLine(a, b);
        for (const QPointF& end : {a, b}) {
            painter.drawEllipse(end, 2.5, 2.5);
        }
        paintLabel(painter, b, QStringLiteral("%1 mm").arg(d.lengthMm(), 0, 'f', 1));
    };
    for (const DistanceMeasurement& d : distances_) {
        if (inPlane(plane, d.start, plane, tolerance) && inPlane(plane, d.end, plane, tolerance)) {
            paintDistance(d);
        }
    }
    for (const EllipseMeasurement& m : ellipses_) {
        if (!inPlane(m.plane, m.ellipse.centre, plane, tolerance)) {
            continue;
        }
        paintEllipse(painter, plane, m.plane, m.ellipse);
        const RoiStatistics& s = m.statistics;
        const QPointF corner = toWidget(plane, m.ellipse.centre) +
                               QPointF(m.ellipse.radiusU, m.ellipse.radiusV) / plane.pixelSize;
        paintLabel(painter, corner,
                   QStringLiteral("Mean %1 %2\nSD %3\nArea %4 mm\u00b2")
                       .arg(s.mean, 0, 'f', 1)
                       .arg(unit)
                       .arg(s.standardDeviation, 0, 'f', 1)
                       .arg(s.areaMm2, 0, 'f', 1));
    }
    if (drawing_) {
        if (kind_ == MeasurementKind::Distance) {
            paintDistance({first_, current_});
        } else {
            paintEllipse(painter, plane, plane, ellipseBetween(first_, current_, plane));
        }
    }
    painter.restore();
}

} // namespace lucent
