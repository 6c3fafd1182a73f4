#include "ui/mpr/MeasurementPainter.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <QPainter>
#include <QPainterPath>

namespace lucent {

namespace {

QColor colourOf(MeasurementLook look) {
    switch (look) {
    case MeasurementLook::Selected:
        return {90, 220, 255};
    case MeasurementLook::ReadOnly:
        return {160, 160, 160};
    case MeasurementLook::Draft:
    case MeasurementLook::Normal:
        break;
    }
    return {255, 230, 80};
}

QPointF toWidget(const SlicePlane& plane, const glm::dvec3& p) {
    const glm::dvec2 px = plane.pixelOf(p);
    return {px.x + 0.5, px.y + 0.5};
}

void paintLabel(QPainter& painter, const QPointF& at, const QString& text) {
    if (text.isEmpty()) {
        return;
    }
    const QRectF box =
        painter.fontMetrics().boundingRect(QRect(0, 0, 400, 100), Qt::AlignLeft, text);
    QRectF placed = box.translated(at + QPointF(8.0, 6.0)).adjusted(-2, -1, 2, 1);
    // Kept inside the view: moved left or up where it would leave it.
    const QRectF view = painter.window();
    placed.moveLeft(std::max(view.left(), std::min(placed.left(), view.right() - placed.width())));
    placed.moveTop(std::max(view.top(), std::min(placed.top(), view.bottom() - placed.height())));
    painter.fillRect(placed, QColor(0, 0, 0, 150));
    painter.drawText(placed, Qt::AlignCenter, text);
}

void paintEllipse(QPainter& painter, const SlicePlane& plane, const Measurement& m) {
    const EllipseRoi e = measurementEllipse(m);
    const double angle = std::atan2(glm::dot(m.plane.u, plane.v), glm::dot(m.plane.u, plane.u));
    painter.save();
    painter.translate(toWidget(plane, e.centre));
    painter.rotate(angle * 180.0 / std::numbers::pi);
    painter.drawEllipse(QPointF(0.0, 0.0), e.radiusU / plane.pixelSize,
                        e.radiusV / plane.pixelSize);
    painter.restore();
}

void paintArrowHead(QPainter& painter, const QPointF& tail, const QPointF& head) {
    const QPointF d = head - tail;
    const double length = std::hypot(d.x(), d.y());
    if (length <= 0.0) {
        return;
    }
    const double angle = std::atan2(d.y(), d.x());
    QPainterPath path(head);
    for (const double side : {-1.0, 1.0}) {
        const double a = angle + std::numbers::pi + side * 0.45;
        path.lineTo(head + 11.0 * QPointF(std::cos(a), std::sin(a)));
        path.moveTo(head);
    }
    painter.drawPath(path);
}

// Where the text goes: beside the point a reader looks at for each kind.
QPointF labelAnchor(const SlicePlane& plane, const Measurement& m) {
    switch (m.kind) {
    case MeasurementKind::Angle:
    case MeasurementKind::Bidirectional:
    case MeasurementKind::Distance:
        return toWidget(plane, m.points[1]);
    case MeasurementKind::CobbAngle:
        return toWidget(plane, 0.5 * (m.points[2] + m.points[3]));
    case MeasurementKind::Arrow:
        return toWidget(plane, m.points[0]);
    case MeasurementKind::Ellipse: {
        const EllipseRoi e = measurementEllipse(m);
        return toWidget(plane, e.centre) +
               QPointF(e.radiusU, e.radiusV) / plane.pixelSize / std::numbers::sqrt2;
    }
    }
    return {};
}

} // namespace

bool measurementInPlane(const Measurement& m, const SlicePlane& plane, double tolerance) {
    const glm::dvec3 a = glm::normalize(m.plane.normal());
    const glm::dvec3 b = glm::normalize(plane.normal());
    return std::abs(glm::dot(a, b)) > 0.9999 && distanceFromPlane(m, plane) <= tolerance;
}

QString measurementOverlayText(const Measurement& m) {
    QStringList lines;
    if (!m.label.empty()) {
        lines << QString::fromStdString(m.label);
    }
    if (m.kind == MeasurementKind::Ellipse) {
        const RoiStatistics& s = m.statistics;
        const QString unit = m.unit.empty() ? QString() : " " + QString::fromStdString(m.unit);
        if (m.suv) {
            lines << QStringLiteral("SUVmax %1").arg(m.suv->max, 0, 'f', 2)
                  << QStringLiteral("SUVpeak %1").arg(m.suv->peak, 0, 'f', 2)
                  << QStringLiteral("SUVmean %1").arg(m.suv->mean, 0, 'f', 2);
        }
        lines << QStringLiteral("Mean %1%2").arg(s.mean, 0, 'f', 1).arg(unit)
              << QStringLiteral("SD %1").arg(s.standardDeviation, 0, 'f', 1)
              << QStringLiteral("Area %1 mm\u00b2").arg(s.areaMm2, 0, 'f', 1);
    } else {
        const QString value = QString::fromStdString(measurementValueText(m));
        if (!value.isEmpty()) {
            lines << value;
        }
    }
    return lines.join('\n');
}

void paintMeasurement(QPainter& painter, const SlicePlane& plane, const Measurement& m,
                      MeasurementLook look) {
    if (m.points.empty()) {
        return;
    }
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    const QColor colour = colourOf(look);
    painter.setPen(QPen(colour, look == MeasurementLook::Selected ? 2.0 : 1.5));
    painter.setBrush(Qt::NoBrush);
    std::vector<QPointF> px;
    for (const glm::dvec3& p : m.points) {
        px.push_back(toWidget(plane, p));
    }
    const bool complete = m.complete();
    if (m.kind == MeasurementKind::Ellipse && complete) {
        paintEllipse(painter, plane, m);
    } else if (m.kind == MeasurementKind::CobbAngle || m.kind == MeasurementKind::Bidirectional) {
        for (std::size_t i = 0; i + 1 < px.size(); i += 2) {
            painter.drawLine(px[i], px[i + 1]);
        }
        if (m.kind == MeasurementKind::CobbAngle && complete) {
            // The two lines' middles joined, dashed: which lines the angle is between.
            painter.save();
            painter.setPen(QPen(colour, 1.0, Qt::DashLine));
            painter.drawLine(0.5 * (px[0] + px[1]), 0.5 * (px[2] + px[3]));
            painter.restore();
        }
    } else {
        for (std::size_t i = 0; i + 1 < px.size(); ++i) {
            painter.drawLine(px[i], px[i + 1]);
        }
        if (m.kind == MeasurementKind::Arrow && px.size() == 2) {
            paintArrowHead(painter, px[0], px[1]);
        }
    }
    if (look != MeasurementLook::ReadOnly) {
        for (const QPointF& p : px) {
            painter.drawEllipse(p, 2.5, 2.5);
        }
    }
    if (complete) {
        paintLabel(painter, labelAnchor(plane, m), measurementOverlayText(m));
    }
    painter.restore();
}

} // namespace lucent
