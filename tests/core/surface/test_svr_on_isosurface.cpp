// The method of spheres on what the extractor makes: the sphere of radius
// a = 10 mm contoured from its signed distance field at h = 0.5 mm. At every
// vertex X the exact SVR of the mesh lies within the research note's bounds of
// the smooth sphere's 12a / (R (8a - 3R)) (with a = |X - centre|: the mesh's
// own radius there): 5e-3 at R = 2 mm, 2e-3 at R = 5 mm. The error halves
// twice over when h halves (the chordal sag, O(h^2)).
#include <QTest>

#include "core/surface/IsosurfaceExtractor.h"
#include "core/surface/SurfaceToVolume.h"
#include "tests/core/surface/IsoVolumes.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr double kA = 10.0;

// The largest relative error of the field against the smooth sphere's.
double worstError(double h, double radius) {
    const TriangleMesh mesh = contour(sphereDistance(kA, h), 0.0).mesh;
    const SvrField field = computeSvrField(mesh, radius);
    double worst = 0.0;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const double a = glm::length(mesh.vertices[v] - kSphereCentre);
        const double smooth = 12.0 * a / (radius * (8.0 * a - 3.0 * radius));
        worst = std::max(worst, std::abs(field.svr[v] / smooth - 1.0));
    }
    return worst;
}

} // namespace

class TestSvrOnIsosurface : public QObject {
    Q_OBJECT

private slots:
    void theContouredSphereMatchesTheSmoothOne_data() {
        QTest::addColumn<double>("radius");
        QTest::addColumn<double>("bound");
        QTest::newRow("R = 2 mm") << 2.0 << 5e-3;
        QTest::newRow("R = 5 mm") << 5.0 << 2e-3;
    }
    void theContouredSphereMatchesTheSmoothOne() {
        QFETCH(double, radius);
        QFETCH(double, bound);
        const double fine = worstError(0.5, radius);
        qInfo("R = %.0f mm: worst relative SVR error %.2e at h = 0.5 mm", radius, fine);
        QVERIFY2(fine < bound, qPrintable(QString::number(fine)));
        const double coarse = worstError(1.0, radius);
        QVERIFY2(coarse / fine > 3.0,
                 qPrintable(QString("h = 1: %1, h = 0.5: %2").arg(coarse).arg(fine)));
    }
};

QTEST_GUILESS_MAIN(TestSvrOnIsosurface)
#include "test_svr_on_isosurface.moc"
