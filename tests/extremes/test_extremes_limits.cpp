// What the CPU ray caster refuses (std::invalid_argument naming the setting,
// exactly what RenderDescription::validate refuses), what it accepts at the
// very edge of each range, and the image metrics at their limits.
#include <QTest>

#include <limits>

#include "tests/extremes/ExtremesScenes.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

} // namespace

class TestExtremesLimits : public QObject {
    Q_OBJECT
    static RenderDescription base(const Volume& v) { return describe(v, rampTf(true), 16); }

private slots:
    void refused_data() {
        QTest::addColumn<int>("which");
        QTest::addColumn<double>("value");
        QTest::addColumn<QString>("word");
        const auto add = [](const char* name, int which, double value, const char* word) {
            QTest::newRow(name) << which << value << QString(word);
        };
        add("step-0", 0, 0.0, "step");
        add("step-negative", 0, -1.0, "step");
        add("step-5e-5", 0, 5e-5, "step");
        add("step-nan", 0, kNaN, "step");
        add("step-inf", 0, kInf, "step");
        add("width-0", 1, 0.0, "image size");
        add("width-16385", 1, 16385.0, "image size");
        add("early-termination-0", 2, 0.0, "early termination");
        add("early-termination-1.5", 2, 1.5, "early termination");
        add("early-termination-nan", 2, kNaN, "early termination");
        add("brick-0", 3, 0.0, "brick size");
        add("zoom-0", 4, 0.0, "zoom");
        add("zoom-negative", 4, -1.0, "zoom");
        add("zoom-inf", 4, kInf, "zoom");
        add("zoom-nan", 4, kNaN, "zoom");
        add("fov-0", 5, 0.0, "field of view");
        add("fov-180", 5, 180.0, "field of view");
        add("fov-nan", 5, kNaN, "field of view");
        add("azimuth-inf", 6, kInf, "azimuth");
        add("iso-nan", 7, kNaN, "iso value");
        add("preclassified-cubic", 8, 0.0, "pre-classification");
        add("tf-opacity-1.5", 9, 1.5, "opacity[1]");
        add("tf-opacity-nan", 9, kNaN, "opacity[1]");
    }
    void refused() {
        QFETCH(int, which);
        QFETCH(double, value);
        QFETCH(QString, word);
        const Volume v = makeVolume({8, 8, 8}, blobs);
        RenderDescription d = base(v);
        switch (which) {
        case 0:
            d.sampling.step = value;
            break;
        case 1:
            d.width = int(value);
            break;
        case 2:
            d.sampling.earlyTermination = value;
            break;
        case 3:
            d.sampling.brickSize = int(value);
            break;
        case 4:
            d.camera.zoom = value;
            break;
        case 5:
            d.camera.fieldOfView = value;
            break;
        case 6:
            d.camera.azimuth = value;
            break;
        case 7:
            d.isoValue = value;
            break;
        case 8:
            d.sampling.classification = Classification::Pre;
            d.sampling.interpolation = Interpolation::Cubic;
            break;
        default:
            d.transferFunction.opacity[1].opacity = value;
            break;
        }
        CpuRayCaster caster(v);
        for (const Precision p : {Precision::Float, Precision::Double}) {
            d.sampling.precision = p;
            try {
                caster.render(d);
                QFAIL("rendered a description validate() refuses");
            } catch (const std::invalid_argument& e) {
                QVERIFY2(QString(e.what()).contains(word),
                         qPrintable(QString("message '%1' does not name %2").arg(e.what(), word)));
            }
        }
    }

    // The edges of each range are accepted and render finite pixels.
    void edgesAccepted() {
        const Volume v = makeVolume({8, 8, 8}, blobs);
        CpuRayCaster caster(v);
        std::vector<RenderDescription> ds(6, base(v));
        ds[0].sampling.step = 1e-4;
        ds[1].sampling.earlyTermination = 1e-12;
        ds[2].sampling.brickSize = 1;
        ds[3].camera.fieldOfView = 179.999;
        ds[4].camera.zoom = 1e-300;
        ds[5].width = 1;
        ds[5].height = 1;
        for (RenderDescription& d : ds) {
            for (const Precision p : {Precision::Float, Precision::Double}) {
                d.sampling.precision = p;
                const RenderResult r = caster.render(d);
                QVERIFY2(badPixels(r.premultiplied, d.transferFunction).isEmpty(),
                         qPrintable(badPixels(r.premultiplied, d.transferFunction)));
            }
        }
    }

    void emptyVolumeRefused() {
        const Volume empty;
        RenderDescription d = describe(empty, rampTf(true), 16);
        try {
            d.validate();
            QFAIL("validated an empty volume");
        } catch (const std::invalid_argument& e) {
            QVERIFY(QString(e.what()).contains("volume is empty"));
        }
    }

    // PSNR of identical images is +inf; of black against white exactly 0 dB.
    void psnrLimits() {
        for (const int size : {1, 11, 64}) {
            const ImageRGBA8 a = ImageRGBA8::filled(size, size, 77);
            const double p = psnr(a, a);
            QVERIFY(std::isinf(p) && p > 0.0);
        }
        QCOMPARE(psnr(ImageRGBA8::filled(16, 16, 0), ImageRGBA8::filled(16, 16, 255)), 0.0);
        ImageRGBA8 b = ImageRGBA8::filled(16, 16, 100);
        b.at(3, 4, 1) = 101; // one LSB in one channel: MSE = 1 / 768
        QVERIFY(std::abs(psnr(ImageRGBA8::filled(16, 16, 100), b) -
                         10.0 * std::log10(255.0 * 255.0 * 768.0)) < 1e-9);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 psnr(ImageRGBA8::filled(0, 0), ImageRGBA8::filled(0, 0)));
    }

    // SSIM of constant images: 1 when equal (the stabilising constants keep
    // 0/0 away), finite and below 1 when not; too small an image is refused.
    void ssimOfConstantImages() {
        for (const int fill : {0, 1, 128, 255}) {
            const ImageRGBA8 a = ImageRGBA8::filled(11, 11, std::uint8_t(fill));
            QCOMPARE(ssim(a, a), 1.0);
            QCOMPARE(ssim(ImageRGBA8::filled(40, 32, std::uint8_t(fill)),
                          ImageRGBA8::filled(40, 32, std::uint8_t(fill))),
                     1.0);
        }
        const double s = ssim(ImageRGBA8::filled(32, 32, 0), ImageRGBA8::filled(32, 32, 255));
        QVERIFY2(std::isfinite(s) && s < 0.01 && s >= -1.0, qPrintable(QString::number(s)));
        try {
            ssim(ImageRGBA8::filled(10, 10, 5), ImageRGBA8::filled(10, 10, 5));
            QFAIL("10x10 accepted");
        } catch (const std::invalid_argument& e) {
            QVERIFY(QString(e.what()).contains("11"));
        }
        try {
            ssim(ImageRGBA8::filled(16, 16, 5), ImageRGBA8::filled(16, 17, 5));
            QFAIL("different sizes accepted");
        } catch (const std::invalid_argument& e) {
            QVERIFY(QString(e.what()).contains("16x16") && QString(e.what()).contains("16x17"));
        }
    }
};

QTEST_GUILESS_MAIN(TestExtremesLimits)
#include "test_extremes_limits.moc"
