// 3D fusion in the CPU reference ray caster (RenderOverlay), on the real 28-slice CT with
// the CT itself as its overlay (resampleOverlay onto its own grid, identity):
//  - opacity 0 gives the base image bit for bit (DVR and MIP, double and float);
//  - a non-zero opacity changes a pixel only where its ray meets an overlay value above
//    the window's low end (the same lattice's MIP tells where), and does change most
//    pixels whose ray meets the top of the window;
//  - MIP: the overlay's maximum over the base's projection by the documented rule;
//  - an overlay moved off part of the grid (NaN there) draws nothing there;
//  - validate() refuses an overlay on another grid, of another type, with no window,
//    and with isosurfaces.
#include <QTest>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/fusion/OverlayResampler.h"
#include "core/io/Catalog.h"
#include "core/mpr/PlaneSampler.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/support/RealData.h"

using namespace lucent;
using lucent::test::maxDifference;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";
constexpr int kSize = 128;

// A MIP whose colour is the value itself, (v + 4000) / 10000, fully opaque.
TransferFunction valueTf() {
    TransferFunction tf;
    tf.name = "value";
    tf.opacity = {{-4000.0, 1.0}, {6000.0, 1.0}};
    tf.colour = {{-4000.0, {0, 0, 0}}, {6000.0, {1, 1, 1}}};
    return tf;
}

} // namespace

class TestFusionRender : public QObject {
    Q_OBJECT

    Volume ct_;
    Volume overlay_; // the CT on its own grid, Float32
    Volume shifted_; // the CT shifted 60 mm along x: it shows where the base has air

    RenderDescription describe(RenderMode mode) const {
        RenderDescription d;
        d.volume = &ct_;
        d.mode = mode;
        d.transferFunction = loadPreset(mode == RenderMode::Dvr ? "ct-bone" : "ct-mip");
        d.width = d.height = kSize;
        d.camera.azimuth = 30.0;
        d.camera.elevation = 15.0;
        return d;
    }

    // Per pixel, the largest CT value its ray's lattice samples meet (a MIP of the
    // same rays, in double).
    std::vector<double> rayMaxima(const RenderDescription& like) const {
        RenderDescription d = like;
        d.mode = RenderMode::Mip;
        d.transferFunction = valueTf();
        d.sampling.precision = Precision::Double;
        d.overlay = RenderOverlay{};
        const RenderResult r = CpuRayCaster(ct_).render(d);
        std::vector<double> out(r.premultiplied.size());
        for (std::size_t i = 0; i < out.size(); ++i) {
            // No sample: alpha 0; mark as below everything.
            out[i] = r.premultiplied[i].a > 0.5f ? double(r.premultiplied[i].r) * 10000.0 - 4000.0
                                                 : -1e30;
        }
        return out;
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        ct_ = loadPath(test::kRealData / kCt);
        QCOMPARE(ct_.dims(), glm::ivec3(512, 512, 28));
        overlay_ = resampleOverlay(ct_, ct_.geometry(), glm::dmat4(1.0));
        QCOMPARE(overlay_.type(), VoxelType::Float32);
        shifted_ = resampleOverlay(ct_, ct_.geometry(),
                                   glm::translate(glm::dmat4(1.0), glm::dvec3(60.0, 0.0, 0.0)));
    }

    void opacityZeroIsTheBaseImage_data() {
        QTest::addColumn<int>("mode");
        QTest::addColumn<int>("precision");
        QTest::addColumn<int>("interp");
        QTest::addColumn<int>("brick");
        QTest::newRow("dvr-double-linear")
            << int(RenderMode::Dvr) << int(Precision::Double) << int(Interpolation::Linear) << 64;
        // Leap cells of 6: the generic float kernel on both sides.
        QTest::newRow("dvr-float-linear")
            << int(RenderMode::Dvr) << int(Precision::Float) << int(Interpolation::Linear) << 6;
        QTest::newRow("dvr-float-cubic")
            << int(RenderMode::Dvr) << int(Precision::Float) << int(Interpolation::Cubic) << 64;
        QTest::newRow("dvr-float-nearest")
            << int(RenderMode::Dvr) << int(Precision::Float) << int(Interpolation::Nearest) << 64;
        QTest::newRow("mip-float-linear")
            << int(RenderMode::Mip) << int(Precision::Float) << int(Interpolation::Linear) << 64;
        QTest::newRow("avg-double-linear") << int(RenderMode::Average) << int(Precision::Double)
                                           << int(Interpolation::Linear) << 64;
    }
    void opacityZeroIsTheBaseImage() {
        QFETCH(int, mode);
        QFETCH(int, precision);
        QFETCH(int, interp);
        QFETCH(int, brick);
        RenderDescription d = describe(RenderMode(mode));
        d.sampling.precision = Precision(precision);
        d.sampling.interpolation = Interpolation(interp);
        d.sampling.brickSize = brick;
        CpuRayCaster caster(ct_);
        const RenderResult base = caster.render(d);
        d.overlay.volume = &overlay_;
        d.overlay.style.colourMap = FusionColourMap::Grey;
        d.overlay.style.center = 300.0;
        d.overlay.style.width = 1000.0;
        d.overlay.style.opacity = 0.0;
        const RenderResult fused = caster.render(d);
        QVERIFY(fused.premultiplied == base.premultiplied);
        QVERIFY(fused.image.pixels == base.image.pixels);
        // The fused render leaps nowhere: more samples for the same picture.
        QVERIFY(fused.stats.samples >= base.stats.samples);
    }

    // A fused DVR render leaps only where neither the base nor the overlay shows: the
    // same picture as taking every sample, from fewer samples. The shifted overlay shows
    // where the base has air, so leaping the base's empty cells alone would show.
    void fusedLeapingChangesNoPixel_data() {
        QTest::addColumn<int>("interp");
        QTest::addColumn<double>("center");
        QTest::newRow("linear-bone") << int(Interpolation::Linear) << 300.0;
        QTest::newRow("linear-soft-tissue") << int(Interpolation::Linear) << 40.0;
        QTest::newRow("cubic-bone") << int(Interpolation::Cubic) << 300.0;
    }
    void fusedLeapingChangesNoPixel() {
        QFETCH(int, interp);
        QFETCH(double, center);
        RenderDescription d = describe(RenderMode::Dvr);
        d.sampling.interpolation = Interpolation(interp);
        d.sampling.brickSize = 16;
        d.overlay.volume = &shifted_;
        d.overlay.style.center = center;
        d.overlay.style.width = 400.0;
        d.overlay.style.opacity = 0.5;
        CpuRayCaster caster(ct_);
        const RenderResult leapt = caster.render(d);
        d.sampling.emptySpaceLeaping = false;
        const RenderResult every = caster.render(d);
        QVERIFY(leapt.premultiplied == every.premultiplied);
        qInfo("%zu samples leaping, %zu without", leapt.stats.samples, every.stats.samples);
        QVERIFY(leapt.stats.samples < every.stats.samples);
    }

    // The fast (SIMD) kernel draws the base; the fused one the same picture within its
    // float rounding.
    void opacityZeroMatchesTheFastKernel() {
        RenderDescription d = describe(RenderMode::Dvr);
        CpuRayCaster caster(ct_);
        const RenderResult base = caster.render(d);
        d.overlay.volume = &overlay_;
        d.overlay.style.width = 1000.0;
        d.overlay.style.opacity = 0.0;
        const float worst = maxDifference(caster.render(d).premultiplied, base.premultiplied);
        QVERIFY2(worst < 1e-4f, qPrintable(QString::number(worst)));
    }

    void overlayShowsOnlyWhereItsRampIsNonZero() {
        RenderDescription d = describe(RenderMode::Dvr);
        d.sampling.precision = Precision::Double;
        CpuRayCaster caster(ct_);
        const RenderResult base = caster.render(d);
        d.overlay.volume = &overlay_;
        d.overlay.style.colourMap = FusionColourMap::HotIron;
        d.overlay.style.center = 300.0; // the ramp: 100 .. 500 HU (this CT reaches 776)
        d.overlay.style.width = 400.0;
        d.overlay.style.opacity = 0.6;
        const RenderResult fused = caster.render(d);
        const std::vector<double> maxima = rayMaxima(d);
        int below = 0, changedBelow = 0, top = 0, changedTop = 0;
        for (std::size_t i = 0; i < maxima.size(); ++i) {
            const bool changed = fused.premultiplied[i] != base.premultiplied[i];
            if (maxima[i] < -1e29) {
                continue; // the ray misses the volume
            }
            if (maxima[i] < 100.0) {
                ++below;
                changedBelow += changed ? 1 : 0;
            } else if (maxima[i] > 500.0) {
                ++top;
                changedTop += changed ? 1 : 0;
            }
        }
        qInfo("largest ray maximum %g", *std::max_element(maxima.begin(), maxima.end()));
        qInfo("rays below the window: %d (%d changed); above it: %d (%d changed)", below,
              changedBelow, top, changedTop);
        QVERIFY(below > 1000 && top > 1000);
        QCOMPARE(changedBelow, 0);
        QVERIFY2(changedTop > top * 9 / 10, qPrintable(QString::number(changedTop)));
    }

    // MIP: P (1 - a) + (c a, a), a = opacity * i / 255, c = grey i / 255, i the entry of the
    // ray's maximum.
    void mipDrawsTheOverlaysMaximumOverTheBase() {
        RenderDescription d = describe(RenderMode::Mip);
        d.transferFunction = valueTf();
        d.sampling.precision = Precision::Double;
        CpuRayCaster caster(ct_);
        const RenderResult base = caster.render(d);
        d.overlay.volume = &overlay_;
        d.overlay.style.colourMap = FusionColourMap::Grey;
        d.overlay.style.center = 500.0;
        d.overlay.style.width = 1500.0;
        d.overlay.style.opacity = 0.7;
        const RenderResult fused = caster.render(d);
        int exact = 0, shown = 0;
        float worst = 0.0f;
        for (std::size_t n = 0; n < base.premultiplied.size(); ++n) {
            const glm::vec4 p = base.premultiplied[n];
            glm::dvec4 expected(p);
            if (p.a > 0.5f) {
                const double m = double(p.r) * 10000.0 - 4000.0;
                const int i = windowToGrey(m, 500.0, 1500.0);
                const double a = 0.7 * i / 255.0, c = i / 255.0;
                expected = glm::dvec4(p) * (1.0 - a) + glm::dvec4(c * a, c * a, c * a, a);
                shown += i > 0 ? 1 : 0;
            }
            float diff = 0.0f;
            for (int ch = 0; ch < 4; ++ch) {
                diff = std::max(diff,
                                float(std::abs(double(fused.premultiplied[n][ch]) - expected[ch])));
            }
            worst = std::max(worst, diff);
            exact += diff < 1e-5f ? 1 : 0;
        }
        qInfo("%d of %zu pixels exact, %d show the overlay, worst %g", exact,
              base.premultiplied.size(), shown, double(worst));
        QVERIFY(shown > 1000);
        // A maximum read back through float lands in the neighbouring entry at most.
        QVERIFY2(worst <= 2.5f / 255.0f, qPrintable(QString::number(worst)));
        QVERIFY(exact >= int(base.premultiplied.size()) * 99 / 100);
    }

    // Shifted by 100 mm along x, the overlay leaves the grid's +x side (the patient's
    // left, about 45 %) NaN: no colour there.
    void noOverlayWhereItHasNoValue() {
        const glm::dmat4 far = glm::translate(glm::dmat4(1.0), glm::dvec3(100.0, 0.0, 0.0));
        const Volume moved = resampleOverlay(ct_, ct_.geometry(), far);
        std::size_t missing = 0;
        for (const float v : moved.voxels<float>()) {
            missing += std::isnan(v) ? 1 : 0;
        }
        QVERIFY(missing > moved.geometry().voxelCount() / 4);
        RenderDescription d = describe(RenderMode::Dvr);
        d.camera.azimuth = 0.0; // from the front: screen right is patient left (+x)
        d.camera.elevation = 0.0;
        CpuRayCaster caster(ct_);
        d.sampling.brickSize = 6;
        const RenderResult base = caster.render(d);
        d.overlay.volume = &moved;
        d.overlay.style.center = 300.0;
        d.overlay.style.width = 600.0;
        d.overlay.style.opacity = 0.8;
        const RenderResult fused = caster.render(d);
        int changed = 0;
        for (std::size_t i = 0; i < base.premultiplied.size(); ++i) {
            QVERIFY(!std::isnan(fused.premultiplied[i].r));
            changed += fused.premultiplied[i] != base.premultiplied[i] ? 1 : 0;
        }
        QVERIFY(changed > 0);
        // The screen's right quarter: rays through NaN only.
        for (int y = 0; y < kSize; ++y) {
            for (int x = kSize * 3 / 4; x < kSize; ++x) {
                const std::size_t i = std::size_t(y) * kSize + x;
                QVERIFY2(fused.premultiplied[i] == base.premultiplied[i],
                         qPrintable(QString("pixel %1,%2").arg(x).arg(y)));
            }
        }
    }

    void validateRefusesBadOverlays() {
        RenderDescription d = describe(RenderMode::Dvr);
        d.overlay.volume = &overlay_;
        auto refuses = [&](const char* word) {
            try {
                d.validate();
            } catch (const std::invalid_argument& e) {
                return std::string(e.what()).find(word) != std::string::npos;
            }
            return false;
        };
        QVERIFY(refuses("overlay window")); // width 0: "auto", never resolved
        resolveOverlayWindow(d.overlay);
        QCOMPARE(d.overlay.style.width, 400.0); // CT: L 40 W 400
        d.validate();
        d.mode = RenderMode::Isosurface;
        QVERIFY(refuses("not iso"));
        d.mode = RenderMode::Dvr;
        VolumeGeometry small = ct_.geometry();
        small.dims = {64, 64, 28};
        const Volume other = resampleOverlay(ct_, small, glm::dmat4(1.0));
        d.overlay.volume = &other;
        QVERIFY(refuses("512x512x28"));
        d.overlay.volume = &ct_; // int16: not resampled
        QVERIFY(refuses("Float32"));
    }
};

QTEST_GUILESS_MAIN(TestFusionRender)
#include "test_fusion_render.moc"
