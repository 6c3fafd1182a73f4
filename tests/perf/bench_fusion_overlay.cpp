// Benchmark (label perf): what an overlay costs (issue 29 part 3), on the real 28-slice CT
// with a copy of it moved by a known rigid transform (4, -7, 10 degrees and 12.5, -30, 8 mm
// about the centre, in a new Frame of Reference) as the overlay, resampled through that
// transform as a fused view does:
//  - MPR: ms per frame of the base alone (sampleImage + windowedGrey + greyToRgb32) and of
//    the base with the overlay (that + sampleOverlay + composeFusion, hot iron at 0.5), at
//    512x512 and 1024x1024, axial and oblique (tilted 20 and 30 degrees), the whole volume
//    fitted into the frame;
//  - 3D: ms per CPU ray-cast frame at 512x512 without and with the overlay
//    (resampleOverlay onto the CT's grid, once, timed apart), DVR ct-bone and MIP ct-mip,
//    each frame turning 5 degrees.
// Medians of LUCENT_BENCH_FRAMES (default 15 MPR, 5 3D) frames after one warm-up. Prints
// the figures; asserts only that the fused frames differ from the plain ones.
#include <QTest>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "app/bench/BenchScenes.h"
#include "core/fusion/FusionCompositor.h"
#include "core/fusion/OverlayResampler.h"
#include "core/io/Catalog.h"
#include "core/mpr/CrosshairSlice.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/support/MovedVolume.h"

using namespace lucent;
using lucent::test::movedCopy;
using lucent::test::rigidAbout;
using Clock = std::chrono::steady_clock;

namespace {

std::filesystem::path realCt() {
    return std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2010";
}

int frames(int fallback) {
    const char* e = std::getenv("LUCENT_BENCH_FRAMES");
    return e != nullptr ? std::max(1, std::atoi(e)) : fallback;
}

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

template <class F> double medianMs(int n, F&& frame) {
    frame(-1); // warm-up
    std::vector<double> ms;
    for (int i = 0; i < n; ++i) {
        const Clock::time_point t0 = Clock::now();
        frame(i);
        ms.push_back(msSince(t0));
    }
    return bench::median(ms);
}

} // namespace

class BenchFusionOverlay : public QObject {
    Q_OBJECT
    Volume ct_, moved_;
    glm::dmat4 move_{1.0};

private slots:
    void initTestCase() {
        if (!std::filesystem::exists(realCt())) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2010");
        }
        ct_ = loadPath(realCt());
        move_ = rigidAbout(volumeCentre(ct_.geometry()), {4.0, -7.0, 10.0}, {12.5, -30.0, 8.0});
        moved_ = movedCopy(ct_, move_);
    }

    void mprFrame_data() {
        QTest::addColumn<int>("size");
        QTest::addColumn<bool>("oblique");
        for (const int size : {512, 1024}) {
            QTest::newRow(qPrintable(QString("%1-axial").arg(size))) << size << false;
            QTest::newRow(qPrintable(QString("%1-oblique").arg(size))) << size << true;
        }
    }
    void mprFrame() {
        QFETCH(int, size);
        QFETCH(bool, oblique);
        const VolumeGeometry& g = ct_.geometry();
        const glm::dmat3 tilt =
            oblique ? glm::dmat3(glm::rotate(
                          glm::rotate(glm::dmat4(1.0), glm::radians(20.0), glm::dvec3(1, 0, 0)),
                          glm::radians(30.0), glm::dvec3(0, 1, 0)))
                    : glm::dmat3(1.0);
        const SlicePlane plane =
            crosshairPlane(g, Orientation::Axial, volumeCentre(g), size, size, tilt);
        FusionStyle style;
        style.colourMap = FusionColourMap::HotIron;
        style.center = 300.0;
        style.width = 400.0;
        style.opacity = 0.5;
        std::vector<Rgb32> plain, fused;
        const int n = frames(15);
        const double baseMs = medianMs(n, [&](int) {
            const std::vector<float> samples = sampleImage(ct_, plane);
            plain = greyToRgb32(windowedGrey(samples, 40.0, 400.0));
        });
        const double fusedMs = medianMs(n, [&](int) {
            const std::vector<float> samples = sampleImage(ct_, plane);
            const std::vector<Rgb32> base = greyToRgb32(windowedGrey(samples, 40.0, 400.0));
            const std::vector<float> overlay = sampleOverlay(moved_, plane, move_);
            fused = composeFusion(base, overlay, size, size, style);
        });
        qInfo("mpr size=%d plane=%s frames=%d base_ms=%.2f fused_ms=%.2f overlay_cost_ms=%.2f",
              size, oblique ? "oblique" : "axial", n, baseMs, fusedMs, fusedMs - baseMs);
        QVERIFY(fused != plain);
    }

    void renderFrame_data() {
        QTest::addColumn<int>("mode");
        QTest::newRow("dvr") << int(RenderMode::Dvr);
        QTest::newRow("mip") << int(RenderMode::Mip);
    }
    void renderFrame() {
        QFETCH(int, mode);
        const Clock::time_point t0 = Clock::now();
        const Volume overlay = resampleOverlay(moved_, ct_.geometry(), move_);
        const double resampleMs = msSince(t0);
        RenderDescription d;
        d.volume = &ct_;
        d.mode = RenderMode(mode);
        d.transferFunction = loadPreset(d.mode == RenderMode::Dvr ? "ct-bone" : "ct-mip");
        d.width = d.height = 512;
        CpuRayCaster caster(ct_);
        const int n = frames(5);
        RenderResult plain, fused;
        const double baseMs = medianMs(n, [&](int i) {
            d.camera.azimuth = 5.0 * i;
            plain = caster.render(d);
        });
        d.overlay.volume = &overlay;
        d.overlay.style.colourMap = FusionColourMap::HotIron;
        d.overlay.style.center = 300.0;
        d.overlay.style.width = 400.0;
        d.overlay.style.opacity = 0.5;
        const double fusedMs = medianMs(n, [&](int i) {
            d.camera.azimuth = 5.0 * i;
            fused = caster.render(d);
        });
        qInfo("render size=512 mode=%s frames=%d base_ms=%.1f fused_ms=%.1f resample_once_ms=%.1f "
              "base_samples=%zu fused_samples=%zu",
              renderModeName(d.mode), n, baseMs, fusedMs, resampleMs, plain.stats.samples,
              fused.stats.samples);
        QVERIFY(fused.image.pixels != plain.image.pixels);
    }
};

QTEST_GUILESS_MAIN(BenchFusionOverlay)
#include "bench_fusion_overlay.moc"
