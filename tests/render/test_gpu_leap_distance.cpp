// The GL caster's distance maps (render/LeapTextures.h): leaps across the
// cube of empty cells the cells' map gives (leap-distance), and samples passed
// over in blocks of 2^3 voxels that show nothing (block-skipping). On the real
// CT, DVR and isosurface, whole and clipped: within 40 dB of the CPU reference,
// within 50 dB of the same render with both switched off (the same samples
// count, so the images are expected to be equal), with fewer samples taken;
// and the maps follow the transfer function and the clip box from frame to frame.
#include <QTest>

#include "core/raycast/LeapReach.h"
#include "render/LeapTextures.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/render/GlTestSupport.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSize = 128;

RenderDescription withoutMaps(RenderDescription d) {
    d.sampling.leapDistance = false;
    d.sampling.blockSkipping = false;
    return d;
}

ClipBox clipOf(const Volume& v) {
    const glm::dvec3 hi(v.dims() - 1);
    return {hi * glm::dvec3(0.2, 0.15, 0.1) + 0.5, hi * glm::dvec3(0.8, 0.7, 0.85) - 0.25};
}

// `on` within 50 dB of `off`; each image saved when it is not.
void verifyLikeOff(const GpuRenderResult& on, const GpuRenderResult& off, const std::string& name) {
    const double p = comparedPsnr(on.frame.image, off.frame.image, name + "-vs-off", 50.0);
    qInfo("%s: %.2f dB against the maps off, largest difference %g, samples %zu against %zu",
          name.c_str(), p, double(maxDifference(on.frame.premultiplied, off.frame.premultiplied)),
          on.frame.stats.samples, off.frame.stats.samples);
    QVERIFY2(p >= 50.0, qPrintable(QString::fromStdString(name) +
                                   QString(": %1 dB against the maps off").arg(p)));
}

} // namespace

class TestGpuLeapDistance : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;

private slots:
    void initTestCase() {
        context_ = OffscreenContext::create();
        qInfo("GL: %s", context_->description().c_str());
    }

    void matchesOffAndTheReference_data() {
        QTest::addColumn<int>("mode");
        QTest::addColumn<int>("interp");
        QTest::addColumn<bool>("clipped");
        for (const bool clipped : {false, true}) {
            const char* c = clipped ? "-clipped" : "";
            QTest::newRow((std::string("dvr-linear") + c).c_str())
                << int(RenderMode::Dvr) << int(Interpolation::Linear) << clipped;
            QTest::newRow((std::string("dvr-nearest") + c).c_str())
                << int(RenderMode::Dvr) << int(Interpolation::Nearest) << clipped;
            QTest::newRow((std::string("iso-linear") + c).c_str())
                << int(RenderMode::Isosurface) << int(Interpolation::Linear) << clipped;
        }
    }
    void matchesOffAndTheReference() {
        QFETCH(int, mode);
        QFETCH(int, interp);
        QFETCH(bool, clipped);
        if (!std::filesystem::exists(philipsCt())) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2020");
        }
        const Volume v = loadPath(philipsCt());
        RenderDescription d = describe(v, loadPreset("ct-bone"), kSize);
        d.camera.azimuth = 25.0;
        d.camera.elevation = 10.0;
        d.mode = RenderMode(mode);
        d.isoValue = 300.0;
        d.sampling.interpolation = Interpolation(interp);
        if (clipped) {
            d.clip = clipOf(v);
        }
        const std::string name = QTest::currentDataTag();
        GpuRayCaster gpu(v);
        const GpuRenderResult on = gpu.renderWithGpuStats(d);
        const GpuRenderResult off = gpu.renderWithGpuStats(withoutMaps(d));
        verifyLikeOff(on, off, name);
        RenderDescription reference = d;
        reference.sampling.precision = Precision::Double;
        const RenderResult cpu = CpuRayCaster(v).render(reference);
        const double p = comparedPsnr(on.frame.image, cpu.image, name, 40.0);
        qInfo("%s: %.2f dB against the CPU reference", name.c_str(), p);
        QVERIFY2(p >= 40.0, qPrintable(QString::fromStdString(name) +
                                       QString(": %1 dB against the CPU reference").arg(p)));
        // DVR passes over samples; an isosurface's leaps each read two.
        if (d.mode == RenderMode::Dvr) {
            QVERIFY2(on.frame.stats.samples < off.frame.stats.samples * 0.8,
                     qPrintable(QString("%1 samples, %2 without the maps")
                                    .arg(on.frame.stats.samples)
                                    .arg(off.frame.stats.samples)));
        } else {
            QVERIFY(on.frame.stats.samples < off.frame.stats.samples);
        }
    }

    // One caster through changes of the transfer function (another visible
    // range) and of the clip box, and back: every frame as a caster that never
    // had the maps draws it.
    // The cells' map holds each cell's code in its low two bits and the reach
    // above them: a line of 100 leapt cells (code 1), one at each end of a
    // brick (code 2), a cell shown in the middle.
    void cellMapHoldsCodeAndReach() {
        const glm::ivec3 n(200, 1, 1);
        std::vector<std::uint8_t> codes(200, 1);
        codes[0] = 2;
        codes[199] = 2;
        codes[100] = 0;
        const std::vector<std::uint8_t> reach = leapReach(codes, n);
        const std::vector<std::uint8_t> bits = cellCodesAndReach(codes, n);
        QCOMPARE(bits.size(), codes.size());
        bool clamped = false;
        for (std::size_t i = 0; i < bits.size(); ++i) {
            QCOMPARE(int(bits[i] & 3), int(codes[i]));
            QCOMPARE(int(bits[i] >> 2), std::min<int>(reach[i], 63));
            clamped = clamped || reach[i] > 63;
        }
        QVERIFY(clamped); // a reach beyond 63 is there to be capped
        QCOMPARE(int(bits[100]), 0);
    }

    void mapsFollowTheTransferFunctionAndClip() {
        if (!std::filesystem::exists(philipsCt())) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2020");
        }
        const Volume v = loadPath(philipsCt());
        RenderDescription bone = describe(v, loadPreset("ct-bone"), kSize);
        bone.camera.azimuth = -30.0;
        RenderDescription soft = bone;
        soft.transferFunction = loadPreset("ct-soft-tissue");
        RenderDescription clipped = soft;
        clipped.clip = clipOf(v);
        GpuRayCaster kept(v), plain(v);
        int step = 0;
        for (const RenderDescription* d : {&bone, &soft, &clipped, &bone}) {
            const GpuRenderResult on = kept.renderWithGpuStats(*d);
            const GpuRenderResult off = plain.renderWithGpuStats(withoutMaps(*d));
            verifyLikeOff(on, off, "change-" + std::to_string(step++));
        }
    }
};

QTEST_GUILESS_MAIN(TestGpuLeapDistance)
#include "test_gpu_leap_distance.moc"
