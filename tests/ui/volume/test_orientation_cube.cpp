// The 3D view's orientation cube: from the front the viewer faces "A"; turned
// by 90 degrees of azimuth, "L" or "R" as LPS says; the head and foot faces
// from above and below; labels read upright and unmirrored; the cube turns the
// way the render does (a ball on the patient's left lands on the side of the L
// face); and the view paints it over the frame (CPU backend, offscreen).
#include <QApplication>
#include <QSignalSpy>
#include <QTest>

#include <cmath>
#include <memory>

#include "tests/support/OffscreenPlatform.h"
#include "tests/ui/volume/BallVolume.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;

namespace {

constexpr int kSize = 200;

OrientationCube cubeFor(double azimuth, double elevation) {
    Camera camera;
    camera.azimuth = azimuth;
    camera.elevation = elevation;
    VolumeGeometry g;
    g.dims = {32, 32, 32};
    return orientationCube(makeViewFrame(g, camera, kSize, kSize), QSizeF(kSize, kSize));
}

// A ball centred on voxel (24, 16, 16) of a 32^3 volume: on the patient's
// left (+x) of the volume's centre.
std::shared_ptr<const Volume> makeBallOnTheLeft() {
    return test::makeBall({24.0, 16.0, 16.0}, 5.0);
}

double brightCentreX(const ImageRGBA8& f) {
    double sum = 0.0, x = 0.0;
    for (int py = 0; py < f.height; ++py) {
        for (int px = 0; px < f.width; ++px) {
            const double a = f.pixels[f.offset(px, py)] / 255.0;
            sum += a;
            x += a * (px + 0.5);
        }
    }
    return sum > 0.0 ? x / sum : -1.0;
}

} // namespace

class TestOrientationCube : public QObject {
    Q_OBJECT

private slots:
    void frontFaceFollowsTheCamera_data() {
        QTest::addColumn<double>("azimuth");
        QTest::addColumn<double>("elevation");
        QTest::addColumn<QChar>("front");
        // The default camera looks at the patient's face: the viewer sees A.
        QTest::newRow("from the front") << 0.0 << 0.0 << QChar('A');
        // Azimuth 90: the eye moves to +x, the patient's left.
        QTest::newRow("turned 90") << 90.0 << 0.0 << QChar('L');
        QTest::newRow("turned -90") << -90.0 << 0.0 << QChar('R');
        QTest::newRow("from behind") << 180.0 << 0.0 << QChar('P');
        // Elevation 90 looks up the head-foot axis from below; -90 down from above.
        QTest::newRow("from below") << 0.0 << 90.0 << QChar('I');
        QTest::newRow("from above") << 0.0 << -90.0 << QChar('S');
    }
    void frontFaceFollowsTheCamera() {
        QFETCH(double, azimuth);
        QFETCH(double, elevation);
        QFETCH(QChar, front);
        const OrientationCube cube = cubeFor(azimuth, elevation);
        QCOMPARE(QChar(cube.front().label), front);
        QVERIFY(std::abs(cube.front().facing - 1.0) < 1e-9);
        // Face on: its centre is the cube's, its letter upright and unmirrored.
        const QPointF middle = cube.area.center();
        QVERIFY(std::hypot(cube.front().centre.x() - middle.x(),
                           cube.front().centre.y() - middle.y()) < 1e-9);
        const QTransform& t = cube.front().labelTransform;
        QVERIFY(t.m11() > 0.0 && std::abs(t.m12()) < 1e-9); // s runs screen right
        QVERIFY(t.m22() > 0.0 && std::abs(t.m21()) < 1e-9); // t runs screen down
        // Exactly one face is seen from straight on; the opposite one not at all.
        int seen = 0;
        for (const OrientationCubeFace& f : cube.faces) {
            seen += f.facing > 1e-6;
        }
        QCOMPARE(seen, 1);
    }

    void sideFacesLieWhereTheirDirectionIs() {
        // From the front, a little from the patient's left and from above: L, A
        // and S are seen; L right of the centre, S above it, A between.
        const OrientationCube cube = cubeFor(30.0, -20.0);
        const QPointF middle = cube.area.center();
        for (const char label : {'L', 'A', 'S'}) {
            QVERIFY2(cube.face(label)->facing > 0.1, &label);
            // Every visible face's letter reads unmirrored from outside the cube.
            QVERIFY(cube.face(label)->labelTransform.determinant() > 0.0);
        }
        for (const char label : {'R', 'P', 'I'}) {
            QVERIFY2(cube.face(label)->facing < 0.0, &label);
        }
        QVERIFY(cube.face('L')->centre.x() > middle.x() + 5.0);
        QVERIFY(cube.face('S')->centre.y() < middle.y() - 5.0);
        QVERIFY(std::abs(cube.face('S')->centre.x() - middle.x()) < 1e-9);
        // Painted back to front: the faces seen come last, the front one at the end.
        QCOMPARE(cube.front().label, 'A');
        for (std::size_t n = 1; n < cube.faces.size(); ++n) {
            QVERIFY(cube.faces[n - 1].facing <= cube.faces[n].facing);
        }
        // It stays inside its corner square, in the view's bottom-left corner.
        QVERIFY(cube.area.left() < kSize / 4.0 && cube.area.bottom() > kSize * 3.0 / 4.0);
        for (const OrientationCubeFace& f : cube.faces) {
            for (const QPointF& c : f.corners) {
                QVERIFY(cube.area.adjusted(-1e-9, -1e-9, 1e-9, 1e-9).contains(c));
            }
        }
    }

    void turnsAsTheRenderDoes_data() {
        QTest::addColumn<double>("azimuth");
        QTest::newRow("front left") << 30.0;
        QTest::newRow("back left") << 150.0;
        QTest::newRow("front right") << -30.0;
    }
    void turnsAsTheRenderDoes() {
        QFETCH(double, azimuth);
        VolumeView view(nullptr, VolumeView::Backend::Cpu);
        view.resize(kSize, kSize);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        view.setVolume(makeBallOnTheLeft());
        view.setTransferFunction(test::whiteBall());
        Camera camera = view.camera();
        camera.azimuth = azimuth;
        QSignalSpy frames(&view, &VolumeView::renderedFrame);
        view.setCamera(camera);
        QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty() && view.lastFrameCurrent(), 30000);
        // The ball on the patient's left is on the side of the cube's L face.
        const double ballX = brightCentreX(view.lastFrame()) - view.lastFrame().width / 2.0;
        const OrientationCube cube = view.orientationMarker();
        const double leftX = cube.face('L')->centre.x() - cube.area.center().x();
        QVERIFY2(std::abs(ballX) > 5.0 && std::abs(leftX) > 5.0,
                 qPrintable(QString("ball %1, L face %2").arg(ballX).arg(leftX)));
        QVERIFY2((ballX > 0.0) == (leftX > 0.0),
                 qPrintable(QString("ball %1, L face %2").arg(ballX).arg(leftX)));
    }

    void viewPaintsItOverTheFrame() {
        VolumeView view(nullptr, VolumeView::Backend::Cpu);
        view.resize(kSize, kSize);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        view.setVolume(makeBallOnTheLeft());
        view.setTransferFunction(test::whiteBall());
        QTRY_VERIFY_WITH_TIMEOUT(!view.lastFrame().empty() && view.lastFrameCurrent(), 30000);
        QVERIFY(view.orientationMarkerShown());
        const QRect corner = view.orientationMarker().area.toAlignedRect();
        const QImage with = view.grabImage().convertToFormat(QImage::Format_RGB32);
        view.setOrientationMarkerShown(false);
        const QImage without = view.grabImage().convertToFormat(QImage::Format_RGB32);
        // Outside its corner the picture is the same; inside, the cube covers the
        // black background with grey faces.
        int changedInside = 0, changedOutside = 0;
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) {
                const bool changed = with.pixel(x, y) != without.pixel(x, y);
                (corner.contains(x, y) ? changedInside : changedOutside) += changed;
            }
        }
        QCOMPARE(changedOutside, 0);
        QVERIFY2(changedInside > corner.width() * corner.height() / 4,
                 qPrintable(QString::number(changedInside)));
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestOrientationCube test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_orientation_cube.moc"
