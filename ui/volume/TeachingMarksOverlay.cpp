#include "ui/volume/TeachingMarksOverlay.h"

#include <QPainterPath>

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "core/scene/ImageProjection.h"

namespace lucent {
namespace {

void paintMark(QPainter& painter, const QRectF& image, const remote::MarkShown& mark,
               const std::vector<QPointF>& p) {
    const double dot = std::max(3.0, image.height() / 120.0);
    QPainterPath path;
    switch (mark.kind) {
    case remote::MarkKind::Arrow: { // tip, tail
        path.moveTo(p[1]);
        path.lineTo(p[0]);
        const double angle = std::atan2(p[0].y() - p[1].y(), p[0].x() - p[1].x());
        const double head = std::max(8.0, image.height() / 30.0);
        for (const double side : {-0.45, 0.45}) {
            path.moveTo(p[0]);
            path.lineTo(p[0] - head * QPointF(std::cos(angle + side), std::sin(angle + side)));
        }
        break;
    }
    case remote::MarkKind::Circle: { // centre, a point of the rim
        const double r = std::hypot(p[1].x() - p[0].x(), p[1].y() - p[0].y());
        path.addEllipse(p[0], r, r);
        break;
    }
    case remote::MarkKind::Freehand:
        path.moveTo(p[0]);
        for (std::size_t n = 1; n < p.size(); ++n) {
            path.lineTo(p[n]);
        }
        break;
    case remote::MarkKind::Text:
        break;
    }
    painter.setBrush(Qt::NoBrush);
    painter.drawPath(path);
    // The mark's anchor: an arrow's tip, a circle's centre, where text stands.
    painter.setBrush(kMarkColour);
    painter.drawEllipse(p[0], dot, dot);
    if (mark.kind == remote::MarkKind::Text) {
        painter.drawText(p[0] + QPointF(8, -8), QString::fromStdString(mark.text));
    }
}

} // namespace

void paintTeachingMarks(QPainter& painter, const QRectF& image, const TeachingMarks& marks,
                        const std::array<double, 12>& projection) {
    auto toView = [&](glm::dvec2 f) {
        return QPointF(image.left() + f.x * image.width(), image.top() + f.y * image.height());
    };
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, true);
    QPen pen(kMarkColour, std::max(2.0, image.height() / 250.0));
    pen.setCapStyle(Qt::RoundCap);
    pen.setJoinStyle(Qt::RoundJoin);
    painter.setPen(pen);
    QFont font = painter.font();
    font.setPixelSize(int(std::max(12.0, image.height() / 28.0)));
    painter.setFont(font);
    for (const auto& [id, mark] : marks.marks()) {
        std::vector<QPointF> points;
        for (const glm::dvec3& anchor : mark.anchors) {
            const auto f = projectToImage(projection, anchor);
            if (!f) {
                break; // behind the eye: not drawn
            }
            points.push_back(toView(*f));
        }
        if (!points.empty() && points.size() == mark.anchors.size()) {
            paintMark(painter, image, mark, points);
        }
    }
    if (const auto& pointer = marks.pointer()) {
        const double r = std::max(5.0, image.height() / 80.0);
        painter.setPen(Qt::NoPen);
        painter.setBrush(kPointerColour);
        painter.drawEllipse(toView(*pointer), r, r);
    }
    painter.restore();
}

} // namespace lucent
