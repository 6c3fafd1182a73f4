// Benchmark (label perf): the CPU time a GPU frame takes before its draw call
// (GpuFrameStats::prepareMs: bricks, tables, uniforms), on the Philips
// 140-slice CT at 512x512 with ct-bone:
//  - camera only: 12 frames of a drag (the cached plan holds);
//  - replanned: the same frames alternating between two opacity curves whose
//    bricks are all resident, so that each frame classifies and plans anew
//    but uploads nothing: what every frame cost before the plan was cached;
//  - under a budget of a third of the volume (levels follow the camera).
// Prints the medians; asserts nothing about time.
#include <QTest>

#include <chrono>
#include <filesystem>

#include "core/io/Catalog.h"
#include "render/GpuRayCaster.h"
#include "render/OffscreenContext.h"
#include "tests/perf/BenchScenes.h"

using namespace lucent;

namespace {

std::filesystem::path philips() {
    return std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2020";
}

struct Overhead {
    double prepareMs = 0.0, castMs = 0.0;
    int planned = 0;
};

// Median prepare and cast time of 12 frames turning 3 degrees each, after one
// frame that sets the scene up; `alternate` swaps the transfer function each frame.
Overhead measure(GpuRayCaster& gpu, RenderDescription d, const TransferFunction* alternate) {
    if (alternate != nullptr) { // both resident before timing
        RenderDescription other = d;
        other.transferFunction = *alternate;
        gpu.renderWithGpuStats(other);
    }
    gpu.renderWithGpuStats(d);
    const TransferFunction base = d.transferFunction;
    std::vector<double> prepare, cast;
    Overhead o;
    for (int frame = 1; frame <= 12; ++frame) {
        d.camera.azimuth = 3.0 * frame;
        if (alternate != nullptr) {
            d.transferFunction = frame % 2 ? *alternate : base;
        }
        const GpuRenderResult r = gpu.renderWithGpuStats(d);
        prepare.push_back(r.gpu.prepareMs);
        cast.push_back(r.gpu.castMs);
        o.planned += r.gpu.bricksPlanned ? 1 : 0;
    }
    o.prepareMs = bench::median(prepare);
    o.castMs = bench::median(cast);
    return o;
}

} // namespace

class BenchFrameOverhead : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;

private slots:
    void initTestCase() { context_ = OffscreenContext::create(); }

    void philipsCtBone() {
        if (!std::filesystem::exists(philips())) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2020");
        }
        const Volume volume = loadPath(philips());
        RenderDescription d;
        d.volume = &volume;
        d.transferFunction = loadPreset("ct-bone");
        d.width = d.height = 512;
        TransferFunction wider = d.transferFunction;
        for (OpacityPoint& p : wider.opacity) {
            p.value -= 100.0;
        }
        GpuRayCaster cached(volume);
        const Overhead camera = measure(cached, d, nullptr);
        GpuRayCaster replanning(volume);
        const Overhead replanned = measure(replanning, d, &wider);
        GpuOptions small;
        small.budgetBytes = volume.byteCount() / 3;
        GpuRayCaster budget(volume, small);
        const Overhead lod = measure(budget, d, nullptr);
        qInfo("frame_overhead: camera_only prepare_ms=%.3f (planned %d of 12, cast_ms=%.1f); "
              "replanned prepare_ms=%.3f (planned %d of 12, cast_ms=%.1f); "
              "budget_third prepare_ms=%.3f (planned %d of 12, cast_ms=%.1f); 512x512, "
              "median of 12",
              camera.prepareMs, camera.planned, camera.castMs, replanned.prepareMs,
              replanned.planned, replanned.castMs, lod.prepareMs, lod.planned, lod.castMs);
        QCOMPARE(camera.planned, 0);
        QCOMPARE(replanned.planned, 12);
    }
};

QTEST_GUILESS_MAIN(BenchFrameOverhead)
#include "bench_frame_overhead.moc"
