// Benchmark (label perf): the CPU ray caster on the Philips 140-slice CT at
// 512x512, ct-bone, shading on, trilinear, step 0.5, anterior view, 6 frames
// turning 5 degrees each; and the accuracy of its first frame against the
// reference (tricubic, step 1/16 voxel, double precision); and the same frames
// through the scalar kernel (SamplingSettings::simd off). Two scenes: ct-bone
// as Lucent defines opacity (per voxel of the smallest spacing), and ct-bone
// with its opacities taken per millimetre, VTK's default unit distance.
// Issue 31's anchors run in the same benchmark, on the same scene, against the
// same reference, three runs alternating with Lucent, one line per run each:
//  - VTK 9.1's vtkFixedPointVolumeRayCastMapper (2 threads), through
//    app/bench/vtk_anchor.py under xvfb-run (app/bench/VtkAnchor.h): time,
//    ratio Lucent / VTK, dB of both. Fails when xvfb-run or python3-vtk9 is
//    missing (packaging/install-deps.sh installs them).
//  - VolPack's shear-warp (libvolpack1-dev, app/bench/VolPackAnchor.h), one
//    thread, classification once outside the timing as Lucent caches its own.
//    Its parallel projection does not line up with Lucent's perspective view:
//    its dB counts that too.
// The scene, the frames and the anchors are lucent_bench's (app/bench), which lucent-cli bench
// interactive runs too. Prints the figures; asserts nothing about time.
#include <QTest>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>

#include "app/bench/BenchFrames.h"
#include "app/bench/BenchScenes.h"
#include "app/bench/VolPackAnchor.h"
#include "app/bench/VtkAnchor.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr const char* kPhilipsCt = "dcm_qa_ct/Philips_S21570/S2020"; // the benchmarks' CT

std::filesystem::path philips() {
    return test::kRealData / kPhilipsCt;
}

std::filesystem::path outDir() {
    return std::filesystem::path(LUCENT_BIN_DIR) / "..";
}

// Lucent's 6 frames turning 5 degrees (median) after one that warms the caches.
bench::TurnFrames lucentFrames(CpuRayCaster& caster, RenderDescription d, bool simd) {
    d.sampling.simd = simd;
    return bench::turnFrames(caster, d);
}

} // namespace

class BenchCpuRender : public QObject {
    Q_OBJECT
    std::optional<Volume> volume_;
    std::optional<bench::VtkAnchor> vtk_; // the volume and the preset as the VTK anchor reads them

private slots:
    void initTestCase() {
        REQUIRE_DATA(kPhilipsCt);
        volume_.emplace(loadPath(philips()));
        vtk_.emplace(*volume_, loadPreset("ct-bone"));
    }

    void philipsCtBone_data() {
        QTest::addColumn<double>("unitMm");
        QTest::newRow("opacity-per-voxel") << 0.0;
        QTest::newRow("opacity-per-mm") << 1.0;
    }
    void philipsCtBone() {
        QFETCH(double, unitMm);
        const Volume& volume = *volume_;
        const RenderDescription d = bench::ctBoneScene(volume, unitMm);
        CpuRayCaster caster(volume);
        const std::string tag = unitMm > 0.0 ? "_per_mm" : "";
        const bench::TurnFrames scalar = lucentFrames(caster, d, false); // no SIMD ray packets
        const auto t0 = Clock::now();
        const RenderResult reference = caster.render(bench::converged(d));
        const double refMs = msSince(t0);
        writePng(reference.image, outDir() / ("bench_cpu_render_reference" + tag + ".png"));
        // VolPack classifies once, outside the timing (Lucent caches its classification).
        std::optional<bench::VolPackAnchor> volpack;
        std::string volpackError;
        const auto t1 = Clock::now();
        try {
            volpack.emplace(volume, d.transferFunction, d.camera, d.width, d.height);
        } catch (const std::exception& e) {
            volpackError = e.what();
        }
        const double classifyMs = msSince(t1);
        // Three runs, Lucent and its anchors alternating: this machine's load comes and goes.
        for (int run = 1; run <= 3; ++run) {
            const bench::TurnFrames lucent = lucentFrames(caster, d, true);
            const ImageRGBA8& lucentImage = lucent.first.frame.image;
            const double lucentDb = psnr(lucentImage, reference.image);
            const double lucentSsim = ssim(lucentImage, reference.image);
            if (run == 1) {
                writePng(lucentImage, outDir() / ("bench_cpu_render_fast" + tag + ".png"));
                qInfo("cpu_render%s: render_ms=%.1f (median of 6, 512x512, 2 threads) "
                      "first_ms=%.1f scalar_render_ms=%.1f samples=%zu psnr_db=%.2f ssim=%.4f vs "
                      "reference (reference took %.0f ms)",
                      tag.c_str(), lucent.medianMs, lucent.firstMs, scalar.medianMs,
                      lucent.first.frame.stats.samples, lucentDb, lucentSsim, refMs);
            }
            bench::VtkAnchorRun vtk;
            try {
                vtk = vtk_->run("fixed", unitMm, d.width, d.height,
                                outDir() / ("bench_cpu_render_vtk" + tag + ".png"));
            } catch (const std::exception& e) {
                QFAIL(e.what());
            }
            qInfo("anchor_vtk_fixed_point%s run %d/3: lucent_ms=%.1f vtk_ms=%.1f ratio=%.3f "
                  "lucent_db=%.2f vtk_db=%.2f lucent_ssim=%.4f vtk_ssim=%.4f (both 2 threads; dB "
                  "and SSIM against the converged reference)",
                  tag.c_str(), run, lucent.medianMs, vtk.renderMs, lucent.medianMs / vtk.renderMs,
                  lucentDb, psnr(vtk.image, reference.image), lucentSsim,
                  ssim(vtk.image, reference.image));
            if (volpack) {
                const bench::TurnFrames v = volPackFrames(*volpack, d);
                const ImageRGBA8& volpackImage = v.first.frame.image;
                writePng(volpackImage, outDir() / ("bench_cpu_render_volpack" + tag + ".png"));
                qInfo("anchor_volpack%s run %d/3: lucent_ms=%.1f volpack_ms=%.1f ratio=%.3f "
                      "lucent_db=%.2f volpack_db=%.2f volpack_ssim=%.4f classify_ms=%.0f axis=%c "
                      "(VolPack: 1 thread, shear-warp, parallel projection: its image does not "
                      "line up with Lucent's perspective one, and its dB counts that)",
                      tag.c_str(), run, lucent.medianMs, v.medianMs, lucent.medianMs / v.medianMs,
                      lucentDb, psnr(volpackImage, reference.image),
                      ssim(volpackImage, reference.image), classifyMs,
                      "ijk"[std::clamp(volpack->lastAxis(), 0, 2)]);
            }
        }
        if (!volpack) {
            QFAIL(volpackError.c_str());
        }
        volPackNearParallel(caster, *volpack, d, tag);
    }

private:
    // VolPack's 6 frames turning 5 degrees; frame 0 (not timed) sizes its buffers.
    static bench::TurnFrames volPackFrames(bench::VolPackAnchor& volpack,
                                           const RenderDescription& d) {
        return bench::turnFrames(
            [&](const RenderDescription& f) {
                GpuRenderResult r;
                r.frame.image = volpack.render(f.camera);
                return r;
            },
            d);
    }

    // To tell VolPack's projection from its sampling: its frame with a 0.5 degree field of
    // view (all but parallel) against Lucent's converged reference with that view.
    static void volPackNearParallel(CpuRayCaster& caster, bench::VolPackAnchor& volpack,
                                    const RenderDescription& d, const std::string& tag) {
        RenderDescription narrow = bench::converged(d);
        narrow.camera.fieldOfView = 0.5;
        const ImageRGBA8 parallel = volpack.render(narrow.camera);
        const ImageRGBA8 parallelReference = caster.render(narrow).image;
        writePng(parallel, outDir() / ("bench_cpu_render_volpack_fov0.5" + tag + ".png"));
        qInfo("anchor_volpack%s at fov 0.5 degrees (near parallel): volpack_db=%.2f "
              "volpack_ssim=%.4f against Lucent's converged reference with that view",
              tag.c_str(), psnr(parallel, parallelReference), ssim(parallel, parallelReference));
    }
};

int main(int argc, char** argv) {
    // A scene renders two converged references and runs both anchors (minutes); QtTest
    // stops a test function after 5 minutes unless told.
    if (qEnvironmentVariableIsEmpty("QTEST_FUNCTION_TIMEOUT")) {
        qputenv("QTEST_FUNCTION_TIMEOUT", "1500000");
    }
    BenchCpuRender bench;
    return QTest::qExec(&bench, argc, argv);
}
#include "bench_cpu_render.moc"
