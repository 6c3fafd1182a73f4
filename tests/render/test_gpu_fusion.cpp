// 3D fusion in the GPU ray caster (RenderOverlay) against the CPU reference (double
// precision), on the real 28-slice CT with the CT itself as its overlay (resampleOverlay
// onto its own grid) and with a copy shifted half off the grid (NaN there): DVR with every
// filter, pre-integration, MIP and average, each colour map. Bounds: PSNR 50 dB and SSIM
// 0.995 (llvmpipe gives 76 dB and more; the unfused images keep to 40 dB). Opacity 0
// gives the GPU's base image; fused leaping changes no pixel; a frame drawn in place is
// cast again when only the overlay changed.
#include <QTest>

#include <glm/gtc/matrix_transform.hpp>

#include "core/fusion/OverlayResampler.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/render/GlTestSupport.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSize = 128;

std::filesystem::path realCt() {
    return std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2010";
}

struct Case {
    const char* name;
    RenderMode mode;
    Interpolation interp;
    bool preintegrate;
    FusionColourMap map;
    bool shifted; // the overlay shifted 60 mm along x: NaN over a quarter of the grid
};

const Case kCases[] = {
    {"dvr-linear-hot-iron", RenderMode::Dvr, Interpolation::Linear, false, FusionColourMap::HotIron,
     false},
    {"dvr-nearest-pet", RenderMode::Dvr, Interpolation::Nearest, false, FusionColourMap::Pet,
     false},
    {"dvr-cubic-rainbow", RenderMode::Dvr, Interpolation::Cubic, false, FusionColourMap::Rainbow,
     false},
    {"dvr-linear-preintegrated", RenderMode::Dvr, Interpolation::Linear, true,
     FusionColourMap::HotIron, false},
    {"dvr-linear-shifted", RenderMode::Dvr, Interpolation::Linear, false, FusionColourMap::HotIron,
     true},
    {"mip-linear-grey", RenderMode::Mip, Interpolation::Linear, false, FusionColourMap::Grey,
     false},
    {"mip-linear-shifted", RenderMode::Mip, Interpolation::Linear, false, FusionColourMap::Pet,
     true},
    {"avg-linear-hot-iron", RenderMode::Average, Interpolation::Linear, false,
     FusionColourMap::HotIron, false},
};

} // namespace

class TestGpuFusion : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;
    Volume ct_, overlay_, shifted_;

    RenderDescription describe(RenderMode mode, const Volume* overlay) const {
        RenderDescription d =
            test::describe(ct_, loadPreset(mode == RenderMode::Dvr ? "ct-bone" : "ct-mip"), kSize);
        d.mode = mode;
        d.camera.azimuth = 30.0;
        d.camera.elevation = 15.0;
        d.overlay.volume = overlay;
        d.overlay.style.center = 300.0; // 100 .. 500 HU: this CT reaches 776
        d.overlay.style.width = 400.0;
        d.overlay.style.opacity = 0.6;
        return d;
    }

private slots:
    void initTestCase() {
        if (!std::filesystem::exists(realCt())) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2010");
        }
        context_ = OffscreenContext::create();
        qInfo("GL: %s", context_->description().c_str());
        ct_ = loadPath(realCt());
        overlay_ = resampleOverlay(ct_, ct_.geometry(), glm::dmat4(1.0));
        shifted_ = resampleOverlay(ct_, ct_.geometry(),
                                   glm::translate(glm::dmat4(1.0), glm::dvec3(60.0, 0.0, 0.0)));
    }

    void matchesTheCpuReference() {
        GpuRayCaster gpu(ct_);
        CpuRayCaster cpu(ct_);
        for (const Case& c : kCases) {
            RenderDescription d = describe(c.mode, c.shifted ? &shifted_ : &overlay_);
            d.sampling.interpolation = c.interp;
            d.sampling.preintegrate = c.preintegrate;
            d.overlay.style.colourMap = c.map;
            const RenderResult g = gpu.render(d);
            d.sampling.precision = Precision::Double;
            const RenderResult r = cpu.render(d);
            const double p = comparedPsnr(g.image, r.image, std::string("fusion-") + c.name, 50.0);
            const double s = ssim(g.image, r.image);
            qInfo("%s: %.2f dB, ssim %.4f", c.name, p, s);
            QVERIFY2(p >= 50.0 && s >= 0.995,
                     qPrintable(QString("%1: psnr %2 dB, ssim %3").arg(c.name).arg(p).arg(s)));
            // The overlay shows: the fused image is not the base's.
            RenderDescription plain = d;
            plain.overlay = RenderOverlay{};
            QVERIFY2(psnr(cpu.render(plain).image, r.image) < 40.0, c.name);
        }
    }

    void opacityZeroIsTheBaseImage() {
        GpuRayCaster gpu(ct_);
        for (const RenderMode mode : {RenderMode::Dvr, RenderMode::Mip}) {
            RenderDescription d = describe(mode, nullptr);
            const RenderResult base = gpu.render(d);
            d.overlay.volume = &overlay_;
            d.overlay.style.opacity = 0.0;
            const RenderResult fused = gpu.render(d);
            QCOMPARE(maxDifference(fused.premultiplied, base.premultiplied), 0.0f);
        }
    }

    // Fused DVR leaps where neither the base nor the overlay shows: the same picture as
    // taking every sample (a bone and a soft-tissue window; the shifted overlay shows where
    // the base has air), from fewer samples.
    void fusedLeapingChangesNoPixel() {
        GpuRayCaster gpu(ct_);
        for (const double center : {300.0, 40.0}) {
            RenderDescription d = describe(RenderMode::Dvr, &shifted_);
            d.overlay.style.center = center;
            const RenderResult leapt = gpu.render(d);
            d.sampling.emptySpaceLeaping = false;
            const RenderResult every = gpu.render(d);
            qInfo("window centre %g: %zu samples leaping, %zu without", center, leapt.stats.samples,
                  every.stats.samples);
            QCOMPARE(maxDifference(leapt.premultiplied, every.premultiplied), 0.0f);
            QVERIFY(leapt.stats.samples < every.stats.samples);
        }
    }

    // drawInPlace keeps the frame it cast while nothing but the background changes: a
    // change of the overlay alone is cast again.
    void drawInPlaceCastsAgainWhenTheOverlayChanges() {
        GpuRayCaster gpu(ct_);
        TestFramebuffer fb(kSize, kSize);
        RenderDescription d = describe(RenderMode::Dvr, &overlay_);
        gpu.drawInPlace(d, fb.whole());
        const ImageRGBA8 first = fb.read();
        QCOMPARE(first.pixels, gpu.render(d).image.pixels);
        d.overlay.style.opacity = 0.0;
        gpu.drawInPlace(d, fb.whole());
        const ImageRGBA8 second = fb.read();
        QVERIFY(second.pixels != first.pixels);
        d.overlay.volume = nullptr;
        QCOMPARE(second.pixels, gpu.render(d).image.pixels);
    }
};

QTEST_GUILESS_MAIN(TestGpuFusion)
#include "test_gpu_fusion.moc"
