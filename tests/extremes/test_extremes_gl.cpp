// The GPU ray caster at the extremes: every scene of ExtremesScenes.h gives
// finite, bounded pixels within 40 dB of the CPU reference (double
// precision); its error shrinks with the step; it refuses what validate() does.
#include <QTest>

#include "render/GpuRayCaster.h"
#include "render/OffscreenContext.h"
#include "tests/extremes/ExtremesScenes.h"

using namespace lucent;
using namespace lucent::test;

class TestExtremesGl : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;

private slots:
    void initTestCase() {
        context_ = OffscreenContext::create();
        qInfo("GL: %s", context_->description().c_str());
    }

    void scenes_data() {
        QTest::addColumn<QString>("name");
        for (const std::string& n : sceneNames()) {
            QTest::newRow(n.c_str()) << QString::fromStdString(n);
        }
    }
    void scenes() {
        QFETCH(QString, name);
        Scene s = makeScene(name.toStdString());
        GpuRenderResult g;
        RenderResult r;
        try {
            RenderDescription d = s.desc;
            d.sampling.precision = Precision::Double;
            r = CpuRayCaster(*s.volume).render(d);
            GpuRayCaster gpu(*s.volume);
            g = gpu.renderWithGpuStats(s.desc);
        } catch (const std::exception& e) {
            QFAIL(qPrintable(name + ": threw " + e.what()));
        }
        const QString bad = badPixels(g.frame.premultiplied, s.desc.transferFunction);
        QVERIFY2(bad.isEmpty(), qPrintable(name + ": " + bad));
        QCOMPARE(int(g.frame.premultiplied.size()), s.desc.width * s.desc.height);
        const double p = psnr(g.frame.image, r.image);
        qInfo("%s: GL against CPU %.2f dB, %zu samples", qPrintable(name), p,
              g.frame.stats.samples);
        QVERIFY2(p >= 40.0, qPrintable(name + QString(": GL %1 dB from the CPU").arg(p)));
    }

    // Step 1e-4 through 2 voxels of constant opacity a: 1 - (1 - a)^2.0001.
    void tinyStepMatchesTheOptics() {
        Scene s = makeScene("step-1e-4-tiny");
        GpuRayCaster gpu(*s.volume);
        for (const double a : {1e-6, 0.3, 1.0}) {
            s.desc.transferFunction = flatTf(a);
            s.desc.sampling.earlyTermination = 1.0;
            const GpuRenderResult g = gpu.renderWithGpuStats(s.desc);
            QVERIFY2(badPixels(g.frame.premultiplied, s.desc.transferFunction).isEmpty(), "bad");
            const double want = 1.0 - std::pow(1.0 - a, 2.0001);
            const double got = centrePixel(g.frame, 15, 15).a;
            QVERIFY2(std::abs(got - want) <= 2e-2 * want,
                     qPrintable(QString("a %1: alpha %2, want %3").arg(a).arg(got).arg(want)));
        }
    }

    // PSNR against a step-1/16 CPU double reference rises with every halving.
    void errorShrinksWithTheStep() {
        const Volume v = makeVolume({32, 32, 32}, blobs);
        RenderDescription d = describe(v, rampTf(true), 48);
        d.camera.azimuth = 25.0;
        d.camera.elevation = 15.0;
        d.sampling.earlyTermination = 1.0;
        RenderDescription fine = d;
        fine.sampling.step = 1.0 / 16.0;
        fine.sampling.precision = Precision::Double;
        const RenderResult reference = CpuRayCaster(v).render(fine);
        GpuRayCaster gpu(v);
        double previous = 0.0;
        QString trace;
        for (const double step : {2.0, 1.0, 0.5, 0.25}) {
            d.sampling.step = step;
            const double p = psnr(gpu.renderWithGpuStats(d).frame.image, reference.image);
            trace += QString(" %1:%2").arg(step).arg(p, 0, 'f', 2);
            QVERIFY2(p > previous, qPrintable("psnr does not rise:" + trace));
            previous = p;
        }
        qInfo("psnr by step:%s", qPrintable(trace));
        QVERIFY2(previous >= 35.0, qPrintable("step 0.25 too far from the reference:" + trace));
    }

    // Out-of-range settings: std::invalid_argument naming the setting, as on the CPU.
    void refusesWhatValidateRefuses() {
        const Volume v = makeVolume({8, 8, 8}, blobs);
        GpuRayCaster gpu(v);
        const auto refuses = [&](RenderDescription d, const char* word) {
            try {
                gpu.renderWithGpuStats(d);
            } catch (const std::invalid_argument& e) {
                return QString(e.what()).contains(word);
            }
            return false;
        };
        RenderDescription d = describe(v, rampTf(true), 16);
        d.sampling.step = 5e-5;
        QVERIFY(refuses(d, "step"));
        d.sampling.step = std::nan("");
        QVERIFY(refuses(d, "step"));
        d = describe(v, rampTf(true), 16);
        d.camera.zoom = 0.0;
        QVERIFY(refuses(d, "zoom"));
        d = describe(v, rampTf(true), 16);
        d.width = 0;
        QVERIFY(refuses(d, "image size"));
        d = describe(v, rampTf(true), 16);
        d.transferFunction.opacity[1].opacity = 1.5;
        QVERIFY(refuses(d, "opacity[1]"));
        d = describe(v, rampTf(true), 16);
        QVERIFY(
            badPixels(gpu.renderWithGpuStats(d).frame.premultiplied, d.transferFunction).isEmpty());
    }
};

QTEST_GUILESS_MAIN(TestExtremesGl)
#include "test_extremes_gl.moc"
