// The camera turned about the patient's head-foot axis (core/scene/Turntable.h): the
// turntable of movies and the rotating MIP, checked on the rays they make (ViewFrame).
#include <QTest>

#include <cmath>
#include <numbers>

#include "core/scene/Turntable.h"
#include "core/scene/ViewFrame.h"

using namespace lucent;

namespace {

VolumeGeometry box() {
    VolumeGeometry g;
    g.dims = {40, 30, 20};
    g.spacing = {1.0, 1.5, 2.0};
    g.origin = {-20.0, 10.0, 300.0};
    return g;
}

bool near(const glm::dvec3& a, const glm::dvec3& b, double tolerance = 1e-9) {
    return glm::length(a - b) <= tolerance;
}

} // namespace

class TestTurntable : public QObject {
    Q_OBJECT
private slots:
    void turntableTurnsTheAzimuth() {
        Camera start;
        start.azimuth = 15.0;
        start.elevation = 20.0;
        start.panUp = 3.0;
        const Camera c = turntableCamera(start, 90.0, 6, 4);
        QCOMPARE(c.azimuth, 75.0);
        QCOMPARE(c.elevation, 20.0);
        QCOMPARE(c.panUp, 3.0);
        QCOMPARE(turntableCamera(start, 90.0, 0, 1).azimuth, 105.0); // 0 frames count as 1
    }

    // 36 frames a turn, 10 degrees each, from a levelled, centred start; frame 36 is frame 0.
    void rotatingMipFrames() {
        Camera start;
        start.azimuth = 355.0;
        start.elevation = -30.0;
        start.zoom = 1.7;
        start.distance = 900.0;
        start.panRight = 12.0;
        start.panUp = -4.0;
        for (const int n : {0, 1, 5, 35, 36, 37, 100}) {
            const Camera c = rotatingMipCamera(start, n);
            QCOMPARE(c.elevation, 0.0);
            QCOMPARE(c.panRight, 0.0);
            QCOMPARE(c.panUp, 0.0);
            QCOMPARE(c.zoom, 1.7);
            QCOMPARE(c.distance, 900.0);
            const double want = std::fmod(355.0 + 10.0 * (n % 36), 360.0);
            QVERIFY2(std::abs(c.azimuth - want) < 1e-9,
                     qPrintable(QString("frame %1: %2, want %3").arg(n).arg(c.azimuth).arg(want)));
            QVERIFY(c.azimuth >= 0.0 && c.azimuth < 360.0);
        }
        QCOMPARE(rotatingMipCamera(start, 36).azimuth, rotatingMipCamera(start, 0).azimuth);
        QCOMPARE(kRotatingMipFrames * kRotatingMipFrameMs, 3600);
    }

    // The eye circles the head-foot axis through the volume's centre: head up on screen,
    // at the centre's height and a constant distance from the axis, looking at it, and
    // turned 10 degrees about +z (seen from the head: anticlockwise) each frame.
    void rotatingMipTurnsAboutTheHeadFootAxis() {
        const VolumeGeometry g = box();
        const glm::dvec3 centre = volumeCentre(g);
        Camera start;
        start.elevation = 25.0;
        double radius = -1.0;
        glm::dvec3 previous(0.0);
        for (int n = 0; n <= kRotatingMipFrames; ++n) {
            const ViewFrame f = makeViewFrame(g, rotatingMipCamera(start, n), 200, 100);
            QVERIFY(near(f.up, glm::dvec3(0, 0, 1)));
            QVERIFY(std::abs(f.eye.z - centre.z) < 1e-9);
            QVERIFY(std::abs(f.forward.z) < 1e-12);
            const glm::dvec3 out = f.eye - centre;
            const double r = std::hypot(out.x, out.y);
            if (radius < 0.0) {
                radius = r;
                // Frame 0 looks from the front (anterior, -y) towards the back.
                QVERIFY(near(f.forward, glm::dvec3(0, 1, 0)));
            }
            QVERIFY(std::abs(r - radius) < 1e-6);
            QVERIFY(near(glm::normalize(-out), f.forward));
            if (n > 0) {
                const double turn =
                    std::atan2(glm::cross(previous, out).z, glm::dot(previous, out)) * 180.0 /
                    std::numbers::pi;
                QVERIFY2(std::abs(turn - 10.0) < 1e-9, qPrintable(QString::number(turn)));
            }
            previous = out;
        }
    }
};

QTEST_GUILESS_MAIN(TestTurntable)
#include "test_turntable.moc"
