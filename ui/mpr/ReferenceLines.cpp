#include "ui/mpr/ReferenceLines.h"

#include <QPainter>
#include <QPen>
#include <QRect>

#include <cmath>

namespace lucent {

std::optional<std::pair<glm::dvec2, glm::dvec2>> referenceLine(const SlicePlane& plane,
                                                               const ReferencePlane& other) {
    const glm::dvec3 n1 = glm::normalize(plane.normal());
    const glm::dvec3 n2 = glm::normalize(other.normal);
    const glm::dvec3 direction = glm::cross(n1, n2);
    // A plane within a degree of this one cuts it nowhere useful.
    if (glm::length(direction) < std::sin(glm::radians(1.0))) {
        return std::nullopt;
    }
    // The point of both planes nearest to this plane's centre: from the centre, move
    // within this plane along the direction that reaches the other plane fastest.
    const glm::dvec3 towards = glm::normalize(glm::cross(direction, n1));
    const double along = glm::dot(other.point - plane.centre, n2) / glm::dot(towards, n2);
    const glm::dvec3 onBoth = plane.centre + towards * along;
    const glm::dvec3 unit = glm::normalize(direction);
    const double reach = 4.0 * plane.pixelSize * (plane.width + plane.height + 1);
    return std::pair{plane.pixelOf(onBoth - unit * reach), plane.pixelOf(onBoth + unit * reach)};
}

void paintReferenceLines(QPainter& painter, const QRect& rect, const SlicePlane& plane,
                         const std::vector<ReferencePlane>& others) {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, true);
    painter.setClipRect(rect);
    for (const ReferencePlane& other : others) {
        const auto line = referenceLine(plane, other);
        if (!line) {
            continue;
        }
        QPen pen(other.colour, 1.0, Qt::DashLine);
        pen.setCosmetic(true);
        painter.setPen(pen);
        const QPointF a(line->first.x + 0.5, line->first.y + 0.5);
        const QPointF b(line->second.x + 0.5, line->second.y + 0.5);
        painter.drawLine(a, b);
        if (!other.label.isEmpty()) {
            // The label where the line enters the view from its first end.
            const QLineF full(a, b);
            for (int step = 0; step <= 200; ++step) {
                const QPointF p = full.pointAt(step / 200.0);
                if (rect.adjusted(4, 14, -14, -4).contains(p.toPoint())) {
                    painter.drawText(p + QPointF(3, -3), other.label);
                    break;
                }
            }
        }
    }
    painter.restore();
}

} // namespace lucent
