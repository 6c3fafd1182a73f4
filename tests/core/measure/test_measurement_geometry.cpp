// Making and reshaping measurements on their plane (core/measure/MeasurementGeometry):
// the bidirectional's short axis stays perpendicular through the long one, an ellipse
// stays centred, points stay in the plane they were drawn on.
#include <QTest>

#include <cmath>

#include "core/measure/MeasurementGeometry.h"

using namespace lucent;

namespace {

// An oblique plane: turned 30 degrees about x, through (5, -3, 40).
SlicePlane obliquePlane() {
    SlicePlane p;
    const double a = 30.0 * M_PI / 180.0;
    p.centre = {5.0, -3.0, 40.0};
    p.u = {1.0, 0.0, 0.0};
    p.v = {0.0, std::cos(a), std::sin(a)};
    p.pixelSize = 0.5;
    p.width = 200;
    p.height = 200;
    return p;
}

bool near(double a, double b, double tolerance = 1e-9) {
    return std::abs(a - b) <= tolerance;
}

} // namespace

class TestMeasurementGeometry : public QObject {
    Q_OBJECT
private slots:
    void bidirectionalShortAxisIsPerpendicularThroughTheMiddle() {
        const SlicePlane plane = obliquePlane();
        const glm::dvec3 a = plane.pointAt(20, 30);
        const glm::dvec3 b = plane.pointAt(120, 30);
        const Measurement m = makeBidirectionalMeasurement(plane, a, b);
        QVERIFY(m.complete());
        QVERIFY(near(bidirectionalLongAxisMm(m), 50.0));
        QVERIFY(near(bidirectionalShortAxisMm(m), 25.0));
        QVERIFY(near(glm::dot(m.points[1] - m.points[0], m.points[3] - m.points[2]), 0.0));
        QVERIFY(near(glm::distance(0.5 * (m.points[2] + m.points[3]), 0.5 * (a + b)), 0.0));
        QVERIFY(distanceFromPlane(m, plane) < 1e-9);
    }

    void bidirectionalHandlesKeepItsShape() {
        const SlicePlane plane = obliquePlane();
        Measurement m =
            makeBidirectionalMeasurement(plane, plane.pointAt(20, 30), plane.pointAt(120, 30));
        // A short-axis end dragged off the perpendicular moves along it only.
        QVERIFY(moveMeasurementPoint(m, 3, plane.pointAt(90, 30 + 35)));
        QVERIFY(near(bidirectionalShortAxisMm(m), (25.0 + 35.0) * 0.5));
        QVERIFY(near(glm::dot(m.points[1] - m.points[0], m.points[3] - m.points[2]), 0.0));
        // A long-axis end turns the long axis; the short axis turns with it.
        QVERIFY(moveMeasurementPoint(m, 1, plane.pointAt(70, 80)));
        QVERIFY(near(bidirectionalLongAxisMm(m), std::hypot(50.0, 50.0) * 0.5));
        QVERIFY(near(bidirectionalShortAxisMm(m), 30.0));
        QVERIFY(near(glm::dot(m.points[1] - m.points[0], m.points[3] - m.points[2]), 0.0));
        // Its middle still crosses the long axis at the same place (half way).
        const glm::dvec3 cross = 0.5 * (m.points[0] + m.points[1]);
        const glm::dvec3 s = glm::normalize(m.points[3] - m.points[2]);
        const glm::dvec3 toCross = cross - m.points[2];
        QVERIFY(near(glm::length(toCross - s * glm::dot(toCross, s)), 0.0, 1e-9));
        // A point off the plane is taken onto it.
        QVERIFY(moveMeasurementPoint(m, 0, plane.pointAt(20, 30) + 7.0 * plane.normal()));
        QVERIFY(distanceFromPlane(m, plane) < 1e-9);
        QVERIFY(!moveMeasurementPoint(m, 4, plane.centre));
    }

    void ellipseFromCornersAndItsHandles() {
        const SlicePlane plane = obliquePlane();
        Measurement m = makeEllipseFromCorners(plane, plane.pointAt(10, 20), plane.pointAt(50, 40));
        EllipseRoi e = measurementEllipse(m);
        QVERIFY(near(e.radiusU, 10.0));
        QVERIFY(near(e.radiusV, 5.0));
        QVERIFY(near(glm::distance(e.centre, plane.pointAt(30, 30)), 0.0));
        // An axis end sets that semi-axis; the centre stays.
        QVERIFY(moveMeasurementPoint(m, 2, plane.pointAt(33, 10)));
        e = measurementEllipse(m);
        QVERIFY(near(e.radiusV, 10.0));
        QVERIFY(near(e.radiusU, 10.0));
        QVERIFY(near(glm::distance(e.centre, plane.pointAt(30, 30)), 0.0));
    }

    void otherKindsMoveThePoint() {
        const SlicePlane plane = obliquePlane();
        Measurement m;
        m.kind = MeasurementKind::Angle;
        m.plane = plane;
        m.points = {plane.pointAt(0, 0), plane.pointAt(10, 0), plane.pointAt(10, 10)};
        QVERIFY(near(measurementAngleDegrees(m), 90.0));
        QVERIFY(moveMeasurementPoint(m, 0, plane.pointAt(0, 10)));
        QVERIFY(near(measurementAngleDegrees(m), 45.0));
    }
};

QTEST_APPLESS_MAIN(TestMeasurementGeometry)
#include "test_measurement_geometry.moc"
