// Benchmark (label perf): the CPU time a GPU frame takes before its draw call
// (GpuFrameStats::prepareMs: bricks, tables, uniforms), on the Philips
// 140-slice CT at 512x512 with ct-bone:
//  - camera only: 12 frames of a drag (the cached plan holds);
//  - replanned: the same frames alternating between two opacity curves whose
//    bricks are all resident, so that each frame classifies and plans anew
//    but uploads nothing: what every frame cost before the plan was cached;
//  - under a budget of a third of the volume (levels follow the camera).
// The drag is lucent_bench's (app/bench/BenchFrames.h), which lucent-cli bench interactive
// runs too. Prints the medians; asserts nothing about time.
#include <QTest>

#include <chrono>
#include <filesystem>

#include "app/bench/BenchFrames.h"
#include "core/io/Catalog.h"
#include "render/GpuRayCaster.h"
#include "render/OffscreenContext.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

constexpr const char* kPhilipsCt = "dcm_qa_ct/Philips_S21570/S2020"; // the benchmarks' CT

std::filesystem::path philips() {
    return test::kRealData / kPhilipsCt;
}

} // namespace

class BenchFrameOverhead : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;

private slots:
    void initTestCase() { context_ = OffscreenContext::create(); }

    void philipsCtBone() {
        REQUIRE_DATA(kPhilipsCt);
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
        const bench::DragOverhead camera = bench::dragOverhead(cached, d);
        GpuRayCaster replanning(volume);
        const bench::DragOverhead replanned = bench::dragOverhead(replanning, d, &wider);
        GpuOptions small;
        small.budgetBytes = volume.byteCount() / 3;
        GpuRayCaster budget(volume, small);
        const bench::DragOverhead lod = bench::dragOverhead(budget, d);
        qInfo("frame_overhead: camera_only prepare_ms=%.3f (planned %d of 12, cast_ms=%.1f); "
              "replanned prepare_ms=%.3f (planned %d of 12, cast_ms=%.1f); "
              "budget_third prepare_ms=%.3f (planned %d of 12, cast_ms=%.1f); 512x512, "
              "median of 12",
              camera.outsideCastMs, camera.planned, camera.castMs, replanned.outsideCastMs,
              replanned.planned, replanned.castMs, lod.outsideCastMs, lod.planned, lod.castMs);
        QCOMPARE(camera.planned, 0);
        QCOMPARE(replanned.planned, 12);
    }
};

QTEST_GUILESS_MAIN(BenchFrameOverhead)
#include "bench_frame_overhead.moc"
