#pragma once
// The orientation marker of the 3D view: a small cube in a corner whose faces
// carry the patient directions (LPS: L = +x, P = +y, S = +z; R, A, I opposite),
// turned by the same camera as the render (core's makeViewFrame), projected
// orthographically so that it keeps its size. Plain geometry plus a QPainter
// drawing over the frame: it works alike on the GPU, CPU and remote backends.

#include <QPointF>
#include <QRectF>
#include <QSizeF>
#include <QTransform>

#include <array>

#include "core/scene/ViewFrame.h"

class QPainter;

namespace lucent {

struct OrientationCubeFace {
    char label = ' ';
    glm::dvec3 normal{0.0};         // outward, patient LPS
    std::array<QPointF, 4> corners; // on screen, view pixels, in the label's reading order
    QPointF centre;                 // on screen
    double facing = 0.0;            // the normal towards the eye: > 0 faces the viewer
    // From the face's own square, s right and t down over [-1, 1], to the screen:
    // the label drawn in it reads unmirrored from outside the cube, turned in
    // quarter turns on its face to stand as upright as it can.
    QTransform labelTransform;
};

struct OrientationCube {
    QRectF area;                              // the corner square it fills
    std::array<OrientationCubeFace, 6> faces; // back to front: paint in this order
    // The face turned most towards the viewer.
    const OrientationCubeFace& front() const { return faces.back(); }
    const OrientationCubeFace* face(char label) const;
};

// The cube for a view of `viewSize` (logical pixels) seen with `frame`, in the
// view's bottom-left corner, its square a sixth of the view's shorter side
// (between 48 and 96 pixels).
OrientationCube orientationCube(const ViewFrame& frame, QSizeF viewSize);

// Draws the faces turned towards the viewer with their letters.
void paintOrientationCube(QPainter& painter, const OrientationCube& cube);

} // namespace lucent
