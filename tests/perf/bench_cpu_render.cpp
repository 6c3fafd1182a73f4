// Benchmark (label perf): the CPU ray caster on the Philips 140-slice CT at
// 512x512, ct-bone, shading on, trilinear, step 0.5, anterior view, 6 frames
// turning 5 degrees each; and the accuracy of its first frame against the
// reference (tricubic, step 1/16 voxel, double precision); and the same frames
// through the scalar kernel (SamplingSettings::simd off). Two scenes: ct-bone
// as Lucent defines opacity (per voxel of the smallest spacing), and ct-bone
// with its opacities taken per millimetre, VTK's default unit distance and the
// scene of the VTK anchor (tests/perf/vtk_anchor.py renders both with
// VTK). Prints the figures; asserts nothing about time.
#include <QTest>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/perf/BenchScenes.h"

using namespace lucent;

class BenchCpuRender : public QObject {
    Q_OBJECT
private slots:
    void philipsCtBone_data() {
        QTest::addColumn<double>("unitMm");
        QTest::newRow("opacity-per-voxel") << 0.0;
        QTest::newRow("opacity-per-mm") << 1.0;
    }
    void philipsCtBone() {
        QFETCH(double, unitMm);
        const std::filesystem::path dir =
            std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2020";
        if (!std::filesystem::exists(dir)) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2020");
        }
        const Volume volume = loadPath(dir);
        RenderDescription d;
        d.volume = &volume;
        d.transferFunction = bench::opacityPerUnit(loadPreset("ct-bone"), volume, unitMm);
        d.sampling.step = 0.5;
        d.sampling.interpolation = Interpolation::Linear;
        CpuRayCaster caster(volume);
        using Clock = std::chrono::steady_clock;
        std::vector<double> ms;
        RenderResult first;
        for (int frame = 0; frame < 7; ++frame) { // frame 0 warms the caches
            RenderDescription f = d;
            f.camera.azimuth = 5.0 * std::max(0, frame - 1);
            const auto t0 = Clock::now();
            RenderResult r = caster.render(f);
            ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
            if (frame == 1) {
                first = std::move(r);
            }
        }
        const double firstMs = ms.front();
        ms.erase(ms.begin());
        std::sort(ms.begin(), ms.end());
        const double median = 0.5 * (ms[2] + ms[3]);
        // The same frames through the scalar kernel (no SIMD ray packets).
        std::vector<double> scalar;
        for (int frame = 0; frame < 6; ++frame) {
            RenderDescription f = d;
            f.camera.azimuth = 5.0 * frame;
            f.sampling.simd = false;
            const auto t0 = Clock::now();
            caster.render(f);
            scalar.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        }
        std::sort(scalar.begin(), scalar.end());
        const double scalarMedian = 0.5 * (scalar[2] + scalar[3]);

        RenderDescription ref = d;
        ref.sampling.step = 1.0 / 16.0;
        ref.sampling.interpolation = Interpolation::Cubic;
        ref.sampling.precision = Precision::Double;
        const auto t0 = Clock::now();
        const RenderResult reference = caster.render(ref);
        const double refMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        const std::filesystem::path out = std::filesystem::path(LUCENT_BIN_DIR) / "..";
        const std::string tag = unitMm > 0.0 ? "_per_mm" : "";
        writePng(first.image, out / ("bench_cpu_render_fast" + tag + ".png"));
        writePng(reference.image, out / ("bench_cpu_render_reference" + tag + ".png"));
        qInfo("cpu_render%s: render_ms=%.1f (median of 6, 512x512, 2 threads) first_ms=%.1f "
              "scalar_render_ms=%.1f samples=%zu "
              "psnr_db=%.2f ssim=%.4f vs reference (reference took %.0f ms)",
              tag.c_str(), median, firstMs, scalarMedian, first.stats.samples,
              psnr(first.image, reference.image), ssim(first.image, reference.image), refMs);
    }
};

QTEST_APPLESS_MAIN(BenchCpuRender)
#include "bench_cpu_render.moc"
