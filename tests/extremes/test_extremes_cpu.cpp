// The CPU ray caster at the extremes, in float and double precision: every
// scene of ExtremesScenes.h gives finite, bounded pixels and the same image in
// both precisions; tiny steps, spikes, flat regions and brick borders give the
// numbers the optics say they must; error shrinks as the step does.
#include <QTest>

#include "tests/extremes/ExtremesScenes.h"

using namespace lucent;
using namespace lucent::test;

namespace {

RenderResult renderIn(CpuRayCaster& caster, RenderDescription d, Precision p) {
    d.sampling.precision = p;
    return caster.render(d);
}

const char* precisionName(Precision p) {
    return p == Precision::Double ? "double" : "float";
}

// 1 - exp(-int tau ds / slope): the opacity of a ray running up a linear ramp
// of `slope` values per voxel through spikeTf(peak), whose extinction integrates
// (over the value) to 2 ((1 - c) ln(1 - c) + c) / c for peak c.
double spikeAlpha(double peak, double slope) {
    const double c = peak;
    const double perHalf = c >= 1.0 ? 1.0 : ((1.0 - c) * std::log(1.0 - c) + c) / c;
    return 1.0 - std::exp(-2.0 * perHalf / slope);
}

} // namespace

class TestExtremesCpu : public QObject {
    Q_OBJECT
private slots:
    void scenes_data() {
        QTest::addColumn<QString>("name");
        for (const std::string& n : sceneNames()) {
            QTest::newRow(n.c_str()) << QString::fromStdString(n);
        }
    }
    // Finite, bounded pixels in both precisions, and float within 40 dB of double.
    void scenes() {
        QFETCH(QString, name);
        RenderResult f, d;
        Scene s;
        try {
            s = makeScene(name.toStdString());
            CpuRayCaster caster(*s.volume);
            d = renderIn(caster, s.desc, Precision::Double);
            f = renderIn(caster, s.desc, Precision::Float);
        } catch (const std::exception& e) {
            QFAIL(qPrintable(name + ": threw " + e.what()));
        }
        for (const RenderResult* r : {&f, &d}) {
            const QString bad = badPixels(r->premultiplied, s.desc.transferFunction);
            QVERIFY2(bad.isEmpty(), qPrintable(name + (r == &f ? " float: " : " double: ") + bad));
            QCOMPARE(int(r->premultiplied.size()), s.desc.width * s.desc.height);
        }
        QVERIFY2(f.stats.samples > 0 || name == "opacity-0", "no sample taken");
        const double p = psnr(f.image, d.image);
        qInfo("%s: float against double %.2f dB, %zu samples", qPrintable(name), p,
              f.stats.samples);
        QVERIFY2(p >= 40.0, qPrintable(name + QString(": float %1 dB from double").arg(p)));
    }

    // Opacity 0 adds nothing, however fine the step.
    void zeroOpacityIsExactlyTransparent() {
        Scene s = makeScene("opacity-0");
        CpuRayCaster caster(*s.volume);
        for (const double step : {1e-3, 0.5, 50.0}) {
            s.desc.sampling.step = step;
            for (const Precision p : {Precision::Float, Precision::Double}) {
                const RenderResult r = renderIn(caster, s.desc, p);
                QCOMPARE(alphaSum(r.premultiplied), 0.0);
                for (const glm::vec4& px : r.premultiplied) {
                    QVERIFY(px == glm::vec4(0.0f));
                }
            }
        }
    }

    void tinyStepMatchesTheOptics_data() {
        QTest::addColumn<double>("opacity");
        QTest::addColumn<int>("precision");
        for (const double a : {1e-6, 0.3, 1.0}) {
            for (const Precision p : {Precision::Float, Precision::Double}) {
                QTest::addRow("a=%g-%s", a, precisionName(p)) << a << int(p);
            }
        }
    }
    // Step 1e-4 through a 3x3x3 volume of constant opacity a: the centre ray
    // crosses 2 voxels in 20001 samples, so alpha = 1 - (1 - a)^2.0001.
    void tinyStepMatchesTheOptics() {
        QFETCH(double, opacity);
        QFETCH(int, precision);
        Scene s = makeScene("step-1e-4-tiny");
        s.desc.transferFunction = flatTf(opacity);
        s.desc.sampling.earlyTermination = 1.0;
        CpuRayCaster caster(*s.volume);
        const RenderResult r = renderIn(caster, s.desc, Precision(precision));
        QVERIFY2(badPixels(r.premultiplied, s.desc.transferFunction).isEmpty(), "bad pixels");
        const double want = 1.0 - std::pow(1.0 - opacity, 2.0001);
        const double got = centrePixel(r, 15, 15).a;
        const double tolerance = Precision(precision) == Precision::Double ? 1e-3 : 2e-2;
        QVERIFY2(std::abs(got - want) <= tolerance * want,
                 qPrintable(QString("alpha %1, want %2").arg(got, 0, 'g', 8).arg(want, 0, 'g', 8)));
        QVERIFY(r.stats.samples >= 20001 || opacity == 1.0); // opacity 1 stops at once
    }

    void spikeMatchesTheOptics_data() {
        QTest::addColumn<double>("peak");
        QTest::addColumn<bool>("preintegrate");
        QTest::addColumn<double>("step");
        QTest::addColumn<int>("precision");
        for (const Precision p : {Precision::Float, Precision::Double}) {
            for (const double step : {2.0, 1.0, 0.5, 0.25}) {
                QTest::addRow("preint-peak1-step%g-%s", step, precisionName(p))
                    << 1.0 << true << step << int(p);
            }
            QTest::addRow("preint-peak0.8-step1-%s", precisionName(p))
                << 0.8 << true << 1.0 << int(p);
            QTest::addRow("post-peak0.8-step0.01-%s", precisionName(p))
                << 0.8 << false << 0.01 << int(p);
        }
    }
    // A ray up a linear ramp (6.25 per voxel) through a spike 2 values wide:
    // pre-integration gets its opacity at any step, plain sampling at a fine one.
    void spikeMatchesTheOptics() {
        QFETCH(double, peak);
        QFETCH(bool, preintegrate);
        QFETCH(double, step);
        QFETCH(int, precision);
        Scene s = makeScene("spike-preint");
        s.desc.transferFunction = spikeTf(peak);
        s.desc.sampling.preintegrate = preintegrate;
        s.desc.sampling.step = step;
        CpuRayCaster caster(*s.volume);
        const RenderResult r = renderIn(caster, s.desc, Precision(precision));
        QVERIFY2(badPixels(r.premultiplied, s.desc.transferFunction).isEmpty(), "bad pixels");
        const double want = spikeAlpha(peak, 200.0 / 32.0);
        const glm::vec4 c = centrePixel(r, 33, 33);
        // Float classifies with tables by design (a 256 x 256 pre-integration
        // table); double integrates each segment exactly.
        const bool isDouble = Precision(precision) == Precision::Double;
        const double tolerance = isDouble       ? (preintegrate ? 1e-4 : 0.01)
                                 : preintegrate ? 0.12
                                                : 0.03;
        QVERIFY2(std::abs(c.a - want) <= tolerance * want,
                 qPrintable(QString("alpha %1, want %2").arg(c.a).arg(want)));
        QVERIFY2(std::abs(c.r - c.a) <= 1e-3f, "white spike: colour equals opacity");
    }

    void equalFrontAndBackPreintegrate_data() {
        QTest::addColumn<double>("step");
        QTest::addColumn<int>("precision");
        for (const Precision p : {Precision::Float, Precision::Double}) {
            for (const double step : {1e-3, 0.5, 3.0}) {
                QTest::addRow("step%g-%s", step, precisionName(p)) << step << int(p);
            }
        }
    }
    // In a constant volume every segment has equal front and back values, so
    // each is the corrected sample 1 - (1 - a)^step: the centre ray's 15 voxels
    // give 1 - (1 - a)^15 in segments, 1 - (1 - a)^(15 + step) in samples
    // (one more sample than segments).
    void equalFrontAndBackPreintegrate() {
        QFETCH(double, step);
        QFETCH(int, precision);
        Scene s = makeScene("preint-equal");
        s.desc.width = s.desc.height = 33;
        s.desc.sampling.step = step;
        s.desc.sampling.earlyTermination = 1.0;
        CpuRayCaster caster(*s.volume);
        const RenderResult pre = renderIn(caster, s.desc, Precision(precision));
        s.desc.sampling.preintegrate = false;
        const RenderResult plain = renderIn(caster, s.desc, Precision(precision));
        QVERIFY2(badPixels(pre.premultiplied, s.desc.transferFunction).isEmpty(), "bad pixels");
        const double a = s.desc.transferFunction.opacityAt(120.0);
        const double segments = std::floor(15.0 / step + 1e-9) * step;
        const double wantPre = 1.0 - std::pow(1.0 - a, segments);
        const double wantPlain = 1.0 - std::pow(1.0 - a, segments + step);
        const double gotPre = centrePixel(pre, 33, 33).a, gotPlain = centrePixel(plain, 33, 33).a;
        QVERIFY2(std::abs(gotPre - wantPre) <= 2e-3 && std::abs(gotPlain - wantPlain) <= 2e-3,
                 qPrintable(QString("pre-integrated %1 (want %2), sampled %3 (want %4)")
                                .arg(gotPre)
                                .arg(wantPre)
                                .arg(gotPlain)
                                .arg(wantPlain)));
    }

    // Samples exactly on brick borders: brick size and leaping change no pixel.
    void brickBorderOnASample() {
        for (const Precision p : {Precision::Float, Precision::Double}) {
            Scene s = makeScene("brick-border");
            CpuRayCaster caster(*s.volume);
            s.desc.sampling.emptySpaceLeaping = false;
            const RenderResult every = renderIn(caster, s.desc, p);
            s.desc.sampling.emptySpaceLeaping = true;
            for (const int brick : {4, 8, 16, 64}) {
                for (const double step : {1.0, 0.5, 0.25}) {
                    s.desc.sampling.brickSize = brick;
                    s.desc.sampling.step = step;
                    const RenderResult r = renderIn(caster, s.desc, p);
                    s.desc.sampling.emptySpaceLeaping = false;
                    const RenderResult ref = renderIn(caster, s.desc, p);
                    s.desc.sampling.emptySpaceLeaping = true;
                    QVERIFY2(
                        r.premultiplied == ref.premultiplied,
                        qPrintable(QString("brick %1 step %2 %3: leaping changed pixels, "
                                           "largest difference %4")
                                       .arg(brick)
                                       .arg(step)
                                       .arg(precisionName(p))
                                       .arg(maxDifference(r.premultiplied, ref.premultiplied))));
                }
            }
            QVERIFY(alphaSum(every.premultiplied) > 10.0);
        }
    }

    void errorShrinksWithTheStep_data() {
        QTest::addColumn<int>("precision");
        QTest::addColumn<int>("interp");
        for (const Precision p : {Precision::Float, Precision::Double}) {
            QTest::addRow("linear-%s", precisionName(p)) << int(p) << int(Interpolation::Linear);
            QTest::addRow("cubic-%s", precisionName(p)) << int(p) << int(Interpolation::Cubic);
        }
    }
    // PSNR against a step-1/16 double reference rises with every halving.
    void errorShrinksWithTheStep() {
        QFETCH(int, precision);
        QFETCH(int, interp);
        const Volume v = makeVolume({32, 32, 32}, blobs);
        RenderDescription d = describe(v, rampTf(true), 48);
        d.camera.azimuth = 25.0;
        d.camera.elevation = 15.0;
        d.sampling.interpolation = Interpolation(interp);
        d.sampling.earlyTermination = 1.0;
        CpuRayCaster caster(v);
        RenderDescription fine = d;
        fine.sampling.step = 1.0 / 16.0;
        const RenderResult reference = renderIn(caster, fine, Precision::Double);
        double previous = 0.0;
        QString trace;
        for (const double step : {2.0, 1.0, 0.5, 0.25}) {
            d.sampling.step = step;
            const double p = psnr(renderIn(caster, d, Precision(precision)).image, reference.image);
            trace += QString(" %1:%2").arg(step).arg(p, 0, 'f', 2);
            QVERIFY2(p > previous, qPrintable("psnr does not rise:" + trace));
            previous = p;
        }
        qInfo("psnr by step:%s", qPrintable(trace));
        QVERIFY2(previous >= 35.0, qPrintable("step 0.25 too far from the reference:" + trace));
    }

    void scaledValuesGiveTheSameImage_data() {
        QTest::addColumn<double>("scale");
        QTest::addColumn<int>("precision");
        for (const double scale : {1e-30, 1e-10, 1e10, 1e30}) {
            for (const Precision p : {Precision::Float, Precision::Double}) {
                QTest::addRow("%g-%s", scale, precisionName(p)) << scale << int(p);
            }
        }
    }
    // Volume and transfer function scaled alike: the same picture, shading included.
    void scaledValuesGiveTheSameImage() {
        QFETCH(double, scale);
        QFETCH(int, precision);
        const Volume unit = scaledBlobs(1.0);
        const Volume scaled = scaledBlobs(scale);
        CpuRayCaster a(unit), b(scaled);
        const RenderResult ra =
            renderIn(a, describe(unit, scaledRampTf(1.0, true)), Precision(precision));
        const RenderResult rb =
            renderIn(b, describe(scaled, scaledRampTf(scale, true)), Precision(precision));
        QVERIFY2(badPixels(rb.premultiplied, rampTf(true)).isEmpty(), "bad pixels");
        const double p = psnr(ra.image, rb.image);
        QVERIFY2(p >= 40.0, qPrintable(QString("scaled by %1: %2 dB").arg(scale).arg(p)));
    }

    // A slab one voxel thin, seen face on: every ray through it takes one sample.
    void thinSlabTakesOneSample() {
        Scene s = makeScene("dims-1xNxN-face");
        s.desc.transferFunction = flatTf(0.3);
        CpuRayCaster caster(*s.volume);
        for (const Precision p : {Precision::Float, Precision::Double}) {
            const RenderResult r = renderIn(caster, s.desc, p);
            const double want = 1.0 - std::pow(0.7, s.desc.sampling.step);
            QVERIFY2(
                std::abs(centrePixel(r, 33, 33).a - want) < 1e-4,
                qPrintable(QString("alpha %1, want %2").arg(centrePixel(r, 33, 33).a).arg(want)));
        }
    }
};

QTEST_GUILESS_MAIN(TestExtremesCpu)
#include "test_extremes_cpu.moc"
