// surfacePoint on the demo head CT (InVesalius' Cranium.inv3): the point lies
// where the CPU ray caster's pixel is half made (pixels under half opacity give
// nothing, opaque ones a point), on bone where a ray meets the skull, and it
// projects back onto its pixel through the frame's projection matrix.
#include <QTest>

#include <filesystem>

#include "core/formats/InVesaliusProject.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/raycast/SurfaceDepth.h"
#include "core/scene/ImageProjection.h"
#include "core/scene/ViewFrame.h"

using namespace lucent;

namespace {

const std::filesystem::path kDemoHead = "/usr/share/doc/invesalius-examples/examples/Cranium.inv3";

// The largest voxel value within `radiusMm` of an LPS point.
double maxValueNear(const Volume& v, const glm::dvec3& lps, double radiusMm) {
    const VolumeGeometry& g = v.geometry();
    const glm::dvec3 c = g.toIndex(lps);
    const glm::ivec3 r(glm::ceil(radiusMm / g.spacing));
    double best = -1e300;
    for (int k = -r.z; k <= r.z; ++k) {
        for (int j = -r.y; j <= r.y; ++j) {
            for (int i = -r.x; i <= r.x; ++i) {
                const glm::ivec3 p = glm::ivec3(glm::round(c)) + glm::ivec3(i, j, k);
                if (glm::any(glm::lessThan(p, glm::ivec3(0))) ||
                    glm::any(glm::greaterThanEqual(p, g.dims)) ||
                    glm::length(g.toPatient(glm::dvec3(p)) - lps) > radiusMm) {
                    continue;
                }
                best = std::max(best, v.value(p.x, p.y, p.z));
            }
        }
    }
    return best;
}

} // namespace

class TestSurfaceDepth : public QObject {
    Q_OBJECT
    std::unique_ptr<Volume> head_;

private slots:
    void initTestCase() {
        if (!std::filesystem::exists(kDemoHead)) {
            QSKIP("the demo head CT is not installed (Debian's invesalius-examples: "
                  "/usr/share/doc/invesalius-examples/examples/Cranium.inv3)");
        }
        head_ = std::make_unique<Volume>(readInVesalius(kDemoHead));
    }

    void agreesWithTheRenderedImage_data() {
        QTest::addColumn<double>("azimuth");
        QTest::newRow("front") << 0.0;
        QTest::newRow("side") << 90.0;
    }
    void agreesWithTheRenderedImage() {
        QFETCH(double, azimuth);
        RenderDescription d;
        d.volume = head_.get();
        d.width = d.height = 96;
        d.transferFunction = loadPreset("ct-bone");
        d.camera.azimuth = azimuth;
        d.sampling.precision = Precision::Double; // the transfer function itself, as surfacePoint
        CpuRayCaster caster(*head_);
        const RenderResult rendered = caster.render(d);
        const ImageProjection projection =
            imageProjection(makeViewFrame(head_->geometry(), d.camera, d.width, d.height));
        int surfaces = 0, empty = 0, onBone = 0;
        for (int y = 0; y < d.height; y += 3) {
            for (int x = 0; x < d.width; x += 3) {
                const double alpha = rendered.premultiplied[std::size_t(y) * d.width + x].a;
                const glm::dvec2 fraction((x + 0.5) / d.width, (y + 0.5) / d.height);
                const auto p = surfacePoint(d, fraction);
                if (alpha < kSurfaceOpacity - 1e-3) {
                    QVERIFY2(!p, qPrintable(QString("pixel %1,%2 of alpha %3 has a surface")
                                                .arg(x)
                                                .arg(y)
                                                .arg(alpha)));
                    ++empty;
                    continue;
                }
                if (alpha < kSurfaceOpacity + 1e-3) {
                    continue; // on the threshold: rounding decides
                }
                QVERIFY2(p, qPrintable(QString("pixel %1,%2 of alpha %3 has no surface")
                                           .arg(x)
                                           .arg(y)
                                           .arg(alpha)));
                ++surfaces;
                // The point projects back onto its pixel.
                const auto uv = projectToImage(projection, *p);
                QVERIFY(uv);
                QVERIFY2(glm::length((*uv - fraction) * glm::dvec2(d.width, d.height)) < 1e-6,
                         qPrintable(QString("pixel %1,%2 projects to %3,%4")
                                        .arg(x)
                                        .arg(y)
                                        .arg(uv->x * d.width)
                                        .arg(uv->y * d.height)));
                onBone += maxValueNear(*head_, *p, 2.0) > 300.0 ? 1 : 0;
            }
        }
        QVERIFY2(surfaces > 100 && empty > 100,
                 qPrintable(QString("%1 surfaces, %2 empty").arg(surfaces).arg(empty)));
        // ct-bone shows the skull through the thin skin: most surface points lie within 2 mm
        // of bone (measured: 148 of 198 from the front, where the face is thick, and more
        // from the side).
        QVERIFY2(onBone > surfaces * 2 / 3,
                 qPrintable(QString("%1 of %2 points near bone").arg(onBone).arg(surfaces)));
    }

    void aRayThroughTheSkullStopsWhereTheValueRisesThroughBone() {
        RenderDescription d;
        d.volume = head_.get();
        d.width = d.height = 200;
        d.transferFunction = loadPreset("ct-bone");
        d.transferFunction.opacity = {{-3024, 0}, {199, 0}, {200, 1}, {3071, 1}};
        // A step opacity: the surface is where the sampled value first passes 200 HU.
        const auto p = surfacePoint(d, {0.5, 0.35});
        QVERIFY(p);
        const ViewFrame frame = makeViewFrame(head_->geometry(), d.camera, d.width, d.height);
        const glm::dvec3 w = rayThroughFraction(frame, {0.5, 0.35}, d.width, d.height);
        const glm::dvec3 before = *p - w * 1.0;
        QVERIFY2(maxValueNear(*head_, *p, 1.0) >= 200.0, "the surface point is not on bone");
        const double hBefore = head_->value(int(std::lround(head_->geometry().toIndex(before).x)),
                                            int(std::lround(head_->geometry().toIndex(before).y)),
                                            int(std::lround(head_->geometry().toIndex(before).z)));
        QVERIFY2(hBefore < 200.0,
                 qPrintable(QString("%1 HU 1 mm before the surface").arg(hBefore)));
        // No opacity at all: nothing anywhere.
        d.transferFunction.opacity = {{-3024, 0}, {3071, 0}};
        QVERIFY(!surfacePoint(d, {0.5, 0.5}));
        // A ray beside the volume meets nothing.
        d.transferFunction = loadPreset("ct-bone");
        QVERIFY(!surfacePoint(d, {0.01, 0.01}));
    }
};

QTEST_APPLESS_MAIN(TestSurfaceDepth)
#include "test_surface_depth.moc"
