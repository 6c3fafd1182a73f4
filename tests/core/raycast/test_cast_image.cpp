// The image loop's shortcut: pixels outside pixelsOfBox get no ray, so every
// pixel whose ray meets the box (or clip box) must lie inside it.
#include <QTest>

#include <array>
#include <random>

#include "core/raycast/CastImage.h"

using namespace lucent;

class TestCastImage : public QObject {
    Q_OBJECT
private slots:
    void everyRayThatMeetsTheBoxIsInsideItsPixels() {
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        VolumeGeometry g;
        g.dims = glm::ivec3(60, 50, 24);
        g.spacing = glm::dvec3(0.7, 0.7, 2.5);
        g.origin = glm::dvec3(-20.0, 13.0, 40.0);
        // Axes tilted a little, as in a gantry-tilted or oblique series.
        g.direction = glm::dmat3(glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 0.98, 0.199),
                                 glm::dvec3(0.0, -0.199, 0.98));
        const glm::dmat3 toIndexLinear =
            glm::inverse(glm::dmat3(g.direction[0] * g.spacing.x, g.direction[1] * g.spacing.y,
                                    g.direction[2] * g.spacing.z));
        const int width = 97, height = 61;
        int culled = 0, met = 0;
        for (int trial = 0; trial < 40; ++trial) {
            Camera camera;
            camera.azimuth = 360.0 * u(rng);
            camera.elevation = 180.0 * u(rng) - 90.0;
            // Zoomed out, fitted, and far in (the box beyond the image).
            camera.zoom = std::array{0.5, 1.0, 3.0, 40.0}[std::size_t(trial % 4)];
            const ViewFrame frame = makeViewFrame(g, camera, width, height);
            RaySetup<double> s;
            s.boxLo = glm::dvec3(0.0);
            s.boxHi = glm::dvec3(g.dims - 1);
            s.clipLo = trial % 3 == 0 ? glm::dvec3(10.5, 4.0, 2.0) : s.boxLo;
            s.clipHi = trial % 3 == 0 ? glm::dvec3(30.0, 49.0, 11.5) : s.boxHi;
            s.dt = 0.5;
            const PixelRect rect = pixelsOfBox(g, frame, s.clipLo, s.clipHi, width, height);
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const bool inside =
                        x >= rect.x0 && x <= rect.x1 && y >= rect.y0 && y <= rect.y1;
                    culled += inside ? 0 : 1;
                    RaySpan span;
                    const glm::dvec3 d = toIndexLinear * frame.rayDirection(x, y, width, height);
                    if (raySpan(s, g.toIndex(frame.eye), d, span) && span.nFirst <= span.nLast) {
                        ++met;
                        if (!inside) {
                            QFAIL(
                                qPrintable(QString("trial %1: pixel %2 %3 outside %4..%5 x %6..%7")
                                               .arg(trial)
                                               .arg(x)
                                               .arg(y)
                                               .arg(rect.x0)
                                               .arg(rect.x1)
                                               .arg(rect.y0)
                                               .arg(rect.y1)));
                        }
                    }
                }
            }
        }
        // The shortcut must also take effect: many pixels culled, many rays met.
        QVERIFY2(culled > 40 * width * height / 4 && met > 40 * width * height / 10,
                 qPrintable(QString("culled %1 met %2").arg(culled).arg(met)));
    }
};

QTEST_APPLESS_MAIN(TestCastImage)
#include "test_cast_image.moc"
