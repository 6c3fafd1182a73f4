// The camera at the extremes (issue 8, item 3): the eye inside the volume, a
// kilometre away, on a face of the volume, on a brick border. Both ray casters
// must give finite, bounded pixels; the GPU within 40 dB of the CPU reference
// (double precision); an eye inside the volume sees what a clip box at the eye
// would leave.
#include <QTest>

#include "core/scene/ViewFrame.h"
#include "render/GpuRayCaster.h"
#include "render/OffscreenContext.h"
#include "tests/extremes/ExtremesScenes.h"

using namespace lucent;
using namespace lucent::test;

namespace {

RenderResult cpuReference(const Volume& volume, RenderDescription d) {
    d.sampling.precision = Precision::Double;
    return CpuRayCaster(volume).render(d);
}

} // namespace

class TestExtremesCamera : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;

    // Checks the CPU (float and double) and the GPU images of `s`; returns the double one.
    RenderResult checkBoth(const Scene& s, const QString& what) {
        RenderResult fast, ref;
        try {
            fast = CpuRayCaster(*s.volume).render(s.desc);
            ref = cpuReference(*s.volume, s.desc);
        } catch (const std::exception& e) {
            QTest::qFail(qPrintable(what + ": the CPU threw " + e.what()), __FILE__, __LINE__);
            return ref;
        }
        for (const RenderResult* r : {&fast, &ref}) {
            const QString bad = badPixels(r->premultiplied, s.desc.transferFunction);
            if (!bad.isEmpty()) {
                QTest::qFail(qPrintable(what + ": CPU " + bad), __FILE__, __LINE__);
            }
        }
        const double cpu = psnr(fast.image, ref.image);
        qInfo("%s: CPU float against double %.2f dB, %zu samples", qPrintable(what), cpu,
              ref.stats.samples);
        if (cpu < 40.0) {
            QTest::qFail(qPrintable(what + QString(": CPU float %1 dB from double").arg(cpu)),
                         __FILE__, __LINE__);
        }
        if (context_) {
            GpuRenderResult g;
            try {
                g = GpuRayCaster(*s.volume).renderWithGpuStats(s.desc);
            } catch (const std::exception& e) {
                QTest::qFail(qPrintable(what + ": GL threw " + e.what()), __FILE__, __LINE__);
                return ref;
            }
            const QString bad = badPixels(g.frame.premultiplied, s.desc.transferFunction);
            if (!bad.isEmpty()) {
                QTest::qFail(qPrintable(what + ": GL " + bad), __FILE__, __LINE__);
            }
            const double gl = psnr(g.frame.image, ref.image);
            qInfo("%s: GL against CPU %.2f dB", qPrintable(what), gl);
            if (gl < 40.0) {
                QTest::qFail(qPrintable(what + QString(": GL %1 dB from the CPU").arg(gl)),
                             __FILE__, __LINE__);
            }
        }
        return ref;
    }

private slots:
    void initTestCase() {
        try {
            context_ = OffscreenContext::create();
            qInfo("GL: %s", context_->description().c_str());
        } catch (const std::exception& e) {
            qWarning("no GL context (%s): the CPU checks run alone", e.what());
        }
    }

    // The centre ray of an eye at j = 12 inside a ramp along j takes the same
    // samples as the centre ray from outside with the clip box starting at
    // j = 12 (both lattices hold j = 12), so the centre pixels agree.
    void eyeInsideSeesWhatAClipAtTheEyeLeaves() {
        Scene inside = scene(rampVolume(33), rampTf(false), 33);
        inside.desc.camera.distance = 4.0; // the centre is j = 16
        inside.desc.sampling.earlyTermination = 1.0;
        const RenderResult in = checkBoth(inside, "eye inside");

        Scene clipped = scene(rampVolume(33), rampTf(false), 33);
        clipped.desc.clip.lo.y = 12.0;
        clipped.desc.sampling.earlyTermination = 1.0;
        const RenderResult out = cpuReference(*clipped.volume, clipped.desc);

        const glm::vec4 a = centrePixel(in, 33, 33), b = centrePixel(out, 33, 33);
        qInfo("centre alpha inside %.6f, clipped from outside %.6f", a.a, b.a);
        QVERIFY(a.a > 0.1f);
        QVERIFY2(glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec4(1e-5f))),
                 qPrintable(QString("inside %1, clipped %2").arg(a.a).arg(b.a)));

        // Nothing behind the eye: the eye inside sees less than the whole ramp.
        Scene whole = scene(rampVolume(33), rampTf(false), 33);
        whole.desc.sampling.earlyTermination = 1.0;
        QVERIFY(centrePixel(cpuReference(*whole.volume, whole.desc), 33, 33).a > a.a);
    }

    // The eye exactly on a brick border and on a sample of the lattice.
    void eyeOnABrickBorder() {
        Scene s = scene(makeVolume({33, 33, 33}, blobs, VoxelType::Int16), rampTf(true), 33);
        s.desc.sampling.brickSize = 8;
        s.desc.sampling.step = 1.0;
        s.desc.camera.distance = 8.0; // eye at j = 8
        s.desc.camera.azimuth = 0.0;
        checkBoth(s, "eye on a brick border");
        s.desc.sampling.interpolation = Interpolation::Cubic;
        checkBoth(s, "eye on a brick border, cubic");
    }

    // The eye in the plane of the volume's face x = 0 (inside and outside the
    // box): the centre column's rays run along the face.
    void eyeOnAFace_data() {
        QTest::addColumn<double>("distance");
        QTest::newRow("outside") << 0.0;
        QTest::newRow("inside") << 4.0;
    }
    void eyeOnAFace() {
        QFETCH(double, distance);
        Scene s = scene(makeVolume({32, 32, 32}, blobs, VoxelType::Int16), rampTf(true), 33);
        s.desc.camera.panRight = -15.5; // the centre is x = 15.5
        s.desc.camera.distance = distance;
        const ViewFrame f = makeViewFrame(s.volume->geometry(), s.desc.camera, 33, 33);
        QCOMPARE(f.eye.x, 0.0);
        checkBoth(s, QString("eye on the face x = 0, distance %1").arg(distance));
    }

    // A kilometre away with the zoom that keeps the volume's size on screen:
    // the projection tends to a parallel one, so 100 m and 1 km agree.
    void kilometreAway() {
        Scene s = scene(makeVolume({32, 32, 32}, blobs, VoxelType::Int16), rampTf(true), 33);
        s.desc.camera.azimuth = 30.0;
        s.desc.camera.elevation = 20.0;
        const double fit = fitDistance(s.volume->geometry(), s.desc.camera, 33, 33);
        RenderResult far[2];
        int n = 0;
        for (const double mm : {1e5, 1e6}) {
            s.desc.camera.distance = mm;
            s.desc.camera.zoom = mm / fit;
            far[n++] = checkBoth(s, QString("%1 m away").arg(mm / 1000.0));
        }
        QVERIFY(alphaSum(far[1].premultiplied) > 10.0);
        const double p = psnr(far[0].image, far[1].image);
        qInfo("100 m against 1 km: %.2f dB", p);
        QVERIFY2(p >= 40.0, qPrintable(QString("100 m and 1 km differ: %1 dB").arg(p)));
    }

    // Panned so far that the volume is out of view: an empty image, no work.
    void pannedAway() {
        Scene s = scene(makeVolume({32, 32, 32}, blobs, VoxelType::Int16), rampTf(true), 33);
        s.desc.camera.panRight = 1e4;
        const RenderResult r = checkBoth(s, "panned away");
        QCOMPARE(alphaSum(r.premultiplied), 0.0);
        QCOMPARE(r.stats.samples, std::size_t(0));
    }

    void validateRefusesBadCameras() {
        Scene s = scene(makeVolume({8, 8, 8}, blobs), rampTf(true), 16);
        const auto refuses = [&](auto change, const char* field) {
            RenderDescription d = s.desc;
            change(d.camera);
            try {
                d.validate();
            } catch (const std::invalid_argument& e) {
                return QString(e.what()).contains(field);
            }
            return false;
        };
        QVERIFY(refuses([](Camera& c) { c.distance = -1.0; }, "distance"));
        QVERIFY(refuses([](Camera& c) { c.distance = std::nan(""); }, "distance"));
        QVERIFY(refuses([](Camera& c) { c.distance = HUGE_VAL; }, "distance"));
        QVERIFY(refuses([](Camera& c) { c.panRight = HUGE_VAL; }, "pan"));
        QVERIFY(refuses([](Camera& c) { c.panUp = std::nan(""); }, "pan"));
    }
};

QTEST_GUILESS_MAIN(TestExtremesCamera)
#include "test_extremes_camera.moc"
