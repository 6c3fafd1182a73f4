#include "ui/volume/OrientationCube.h"

#include <algorithm>
#include <cmath>

#include <QFont>
#include <QPainter>
#include <QPainterPath>

namespace lucent {

namespace {

struct FaceAxes {
    char label;
    glm::dvec3 normal;
    glm::dvec3 up; // the label's up on the face when it stands; its right is up x normal
};

// Side faces stand head up; the head and foot faces have anterior up, as the
// patient's top and bottom seen from above and from below.
constexpr std::array<FaceAxes, 6> kFaces{{
    {'L', {1, 0, 0}, {0, 0, 1}},
    {'R', {-1, 0, 0}, {0, 0, 1}},
    {'P', {0, 1, 0}, {0, 0, 1}},
    {'A', {0, -1, 0}, {0, 0, 1}},
    {'S', {0, 0, 1}, {0, -1, 0}},
    {'I', {0, 0, -1}, {0, -1, 0}},
}};

constexpr double kMinSide = 48.0;
constexpr double kMaxSide = 96.0;
constexpr double kMargin = 8.0;

// A face tinted by its axis (left-right reddish, front-back greenish, head-foot
// bluish), muted for a dim room and brighter the more it faces the viewer.
QColor faceColour(const glm::dvec3& normal, double facing) {
    const glm::dvec3 axis = glm::abs(normal);
    const double light = 0.55 + 0.45 * std::clamp(facing, 0.0, 1.0);
    const auto channel = [&](double tint) {
        return int(std::lround((70.0 + 60.0 * tint) * light));
    };
    return {channel(axis.x), channel(axis.y), channel(axis.z), 220};
}

} // namespace

const OrientationCubeFace* OrientationCube::face(char label) const {
    for (const OrientationCubeFace& f : faces) {
        if (f.label == label) {
            return &f;
        }
    }
    return nullptr;
}

OrientationCube orientationCube(const ViewFrame& frame, QSizeF viewSize) {
    OrientationCube cube;
    const double side =
        std::clamp(std::min(viewSize.width(), viewSize.height()) / 6.0, kMinSide, kMaxSide);
    cube.area = QRectF(kMargin, viewSize.height() - kMargin - side, side, side);
    const QPointF middle = cube.area.center();
    // A unit cube (half side 1) seen from any side stays within sqrt(3) of its centre.
    const double scale = 0.5 * side / std::sqrt(3.0);
    const auto project = [&](const glm::dvec3& p) {
        return middle + QPointF(glm::dot(p, frame.right), -glm::dot(p, frame.up)) * scale;
    };
    const glm::dvec3 towardsEye = -frame.forward;
    for (std::size_t n = 0; n < kFaces.size(); ++n) {
        const FaceAxes& axes = kFaces[n];
        // The label's up: the face's own, turned in quarter turns about the normal
        // to stand as upright on screen as it can (a quarter turn keeps it unmirrored).
        glm::dvec3 up = axes.up;
        for (const glm::dvec3& turned :
             {glm::cross(axes.normal, axes.up), -axes.up, glm::cross(axes.up, axes.normal)}) {
            if (glm::dot(turned, frame.up) > glm::dot(up, frame.up) + 1e-9) {
                up = turned;
            }
        }
        const glm::dvec3 right = glm::cross(up, axes.normal);
        OrientationCubeFace& f = cube.faces[n];
        f.label = axes.label;
        f.normal = axes.normal;
        f.facing = glm::dot(axes.normal, towardsEye);
        f.centre = project(axes.normal);
        // Top left, top right, bottom right, bottom left as the label reads.
        f.corners = {project(axes.normal - right + up), project(axes.normal + right + up),
                     project(axes.normal + right - up), project(axes.normal - right - up)};
        const QPointF sAxis = project(axes.normal + right) - f.centre;
        const QPointF tAxis = project(axes.normal - up) - f.centre;
        f.labelTransform =
            QTransform(sAxis.x(), sAxis.y(), tAxis.x(), tAxis.y(), f.centre.x(), f.centre.y());
    }
    std::sort(cube.faces.begin(), cube.faces.end(),
              [](const OrientationCubeFace& a, const OrientationCubeFace& b) {
                  return a.facing < b.facing;
              });
    return cube;
}

void paintOrientationCube(QPainter& painter, const OrientationCube& cube) {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, true);
    painter.setRenderHint(QPainter::TextAntialiasing, true);
    // The letters are drawn in a 64-unit square mapped onto each face.
    constexpr double kUnits = 32.0;
    QFont font = painter.font();
    font.setBold(true);
    font.setPixelSize(40);
    for (const OrientationCubeFace& f : cube.faces) {
        if (f.facing <= 1e-3) {
            continue; // turned away, or edge on
        }
        const QTransform base = painter.transform();
        QPolygonF outline;
        for (const QPointF& c : f.corners) {
            outline << c;
        }
        painter.setPen(QPen(QColor(20, 20, 20, 200), 1.0));
        painter.setBrush(faceColour(f.normal, f.facing));
        painter.drawPolygon(outline);
        painter.setTransform(QTransform::fromScale(1.0 / kUnits, 1.0 / kUnits) * f.labelTransform *
                             base);
        painter.setFont(font);
        painter.setPen(
            QColor(235, 235, 235, int(std::lround(255 * std::min(1.0, 2.0 * f.facing)))));
        painter.drawText(QRectF(-kUnits, -kUnits, 2 * kUnits, 2 * kUnits), Qt::AlignCenter,
                         QString(QChar::fromLatin1(f.label)));
        painter.setTransform(base);
    }
    painter.restore();
}

} // namespace lucent
