#include "ui/mpr/SliceOverlay.h"

#include <cmath>

#include <QFontMetrics>
#include <QPainter>

namespace lucent {

QColor orientationColour(Orientation orientation) {
    switch (orientation) {
    case Orientation::Axial:
        return {230, 80, 80};
    case Orientation::Coronal:
        return {90, 200, 90};
    case Orientation::Sagittal:
        return {230, 200, 60};
    }
    return Qt::white;
}

double scaleBarLengthMm(double pixelSize, double maxPixels) {
    if (!(pixelSize > 0.0) || !(maxPixels > 0.0)) {
        return 0.0;
    }
    const double maxMm = maxPixels * pixelSize;
    const double decade = std::pow(10.0, std::floor(std::log10(maxMm)));
    for (const double factor : {5.0, 2.0, 1.0}) {
        if (factor * decade <= maxMm * (1.0 + 1e-12)) {
            return factor * decade;
        }
    }
    return decade;
}

QStringList seriesOverlayLines(const SeriesInfo& info) {
    QStringList lines;
    auto add = [&lines](const std::string& text) {
        if (!text.empty()) {
            lines << QString::fromStdString(text);
        }
    };
    add(info.patientName);
    if (!info.patientId.empty()) {
        lines << QStringLiteral("ID %1").arg(QString::fromStdString(info.patientId));
    }
    const QString date = QString::fromStdString(formatStudyDate(info.studyDate));
    if (!date.isEmpty()) {
        lines << date;
    }
    const QString series = QString::fromStdString(info.modality + " " + info.description).trimmed();
    if (!series.isEmpty()) {
        lines << series;
    }
    if (info.pet) {
        // The unit of every value shown (window, ROI); why not SUVbw is told once on opening.
        const QString unit = QString::fromStdString(info.pet->unit());
        lines << (info.pet->inSuv()
                      ? unit
                      : QStringLiteral("%1 (not SUVbw)")
                            .arg(unit.isEmpty() ? QStringLiteral("stored units") : unit));
    }
    return lines;
}

namespace {

void paintCrosshair(QPainter& painter, const QRect& rect, const SliceOverlay& o) {
    const SlicePlane& p = o.plane;
    const glm::dvec2 c = p.pixelOf(o.crosshair);
    const QPointF centre(std::floor(c.x) + 0.5, std::floor(c.y) + 0.5);
    const glm::dvec3 n = p.normal();
    const double gap = 12.0;
    const double reach = rect.width() + rect.height() + std::abs(c.x) + std::abs(c.y);
    for (const Orientation other :
         {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
        if (other == o.orientation) {
            continue;
        }
        // The other plane cuts this one along n x n_other, through the crosshair point.
        const glm::dvec3 along = glm::cross(n, o.normals[static_cast<std::size_t>(other)]);
        const glm::dvec2 d(glm::dot(along, p.u), glm::dot(along, p.v));
        if (glm::length(d) < 1e-6) {
            continue;
        }
        const glm::dvec2 unit = glm::normalize(d);
        const QPointF dir(unit.x, unit.y);
        QColor colour = orientationColour(other);
        colour.setAlpha(170);
        painter.setPen(QPen(colour, 1.0));
        painter.drawLine(centre + dir * gap, centre + dir * reach);
        painter.drawLine(centre - dir * gap, centre - dir * reach);
    }
}

} // namespace

void paintScaleBar(QPainter& painter, const QRect& rect, double pixelSize) {
    const double mm = scaleBarLengthMm(pixelSize, rect.width() / 4.0);
    if (mm <= 0.0) {
        return;
    }
    const double length = mm / pixelSize;
    const double y = rect.bottom() - 22.5;
    const double x0 = rect.center().x() - 0.5 * length;
    painter.setPen(QPen(QColor(220, 220, 220), 1.0));
    painter.drawLine(QPointF(x0, y), QPointF(x0 + length, y));
    for (const double x : {x0, x0 + length}) {
        painter.drawLine(QPointF(x, y - 4.0), QPointF(x, y));
    }
    const QString text =
        mm >= 10.0 ? QStringLiteral("%1 cm").arg(mm / 10.0) : QStringLiteral("%1 mm").arg(mm);
    painter.drawText(QRectF(x0, y - 20.0, length, 16.0), Qt::AlignCenter, text);
}

void paintCurvedPath(QPainter& painter, const SlicePlane& plane,
                     const std::vector<glm::dvec3>& points) {
    if (points.empty()) {
        return;
    }
    QPolygonF line;
    for (const glm::dvec3& p : points) {
        const glm::dvec2 at = plane.pixelOf(p);
        line << QPointF(at.x, at.y);
    }
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(QColor(80, 200, 255), 1.5));
    painter.drawPolyline(line);
    painter.setBrush(QColor(80, 200, 255));
    for (const QPointF& p : line) {
        painter.drawEllipse(p, 2.5, 2.5);
    }
    painter.setBrush(Qt::NoBrush);
}

void paintSliceOverlay(QPainter& painter, const QRect& rect, const SliceOverlay& o) {
    paintCrosshair(painter, rect, o);
    // A frame in the view's own colour.
    painter.setPen(QPen(orientationColour(o.orientation), 1.0));
    painter.drawRect(QRectF(rect).adjusted(0.5, 0.5, -0.5, -0.5));

    // Orientation letters at the middle of each edge: they follow oblique planes.
    QFont font = painter.font();
    font.setBold(true);
    painter.setFont(font);
    painter.setPen(QColor(255, 210, 120));
    const QRect inner = rect.adjusted(6, 4, -6, -4);
    auto label = [](const glm::dvec3& d) { return QString::fromStdString(directionLabel(d)); };
    painter.drawText(inner, Qt::AlignLeft | Qt::AlignVCenter, label(-o.plane.u));
    painter.drawText(inner, Qt::AlignRight | Qt::AlignVCenter, label(o.plane.u));
    painter.drawText(inner, Qt::AlignTop | Qt::AlignHCenter, label(-o.plane.v));
    painter.drawText(inner, Qt::AlignBottom | Qt::AlignHCenter, label(o.plane.v));

    font.setBold(false);
    painter.setFont(font);
    painter.setPen(QColor(220, 220, 220));
    painter.drawText(inner, Qt::AlignTop | Qt::AlignLeft, o.topLeft.join(u'\n'));
    painter.drawText(inner, Qt::AlignTop | Qt::AlignRight, o.topRight.join(u'\n'));
    // A corner line that would run under the bottom orientation letter breaks
    // at its double spaces instead.
    const QFontMetrics metrics(font);
    const int room = inner.width() / 2 - metrics.horizontalAdvance(label(o.plane.v)) - 4;
    const auto fitted = [&](QString text) {
        if (metrics.horizontalAdvance(text) > room) {
            text.replace(QStringLiteral("  "), QStringLiteral("\n"));
        }
        return text;
    };
    painter.drawText(inner, Qt::AlignBottom | Qt::AlignLeft, fitted(o.bottomLeft));
    painter.drawText(inner, Qt::AlignBottom | Qt::AlignRight, fitted(o.bottomRight));
    paintScaleBar(painter, rect, o.plane.pixelSize);
}

} // namespace lucent
