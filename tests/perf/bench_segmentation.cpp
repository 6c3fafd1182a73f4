// Benchmark (label perf): the segmentation effects on the Philips 512 x 512 x 140 head CT.
// Grow from seeds (fast GrowCut): the first result and the update after one more stroke, on
// the whole volume and on the box round the strokes (5 mm); margin 5 mm on the bone
// threshold; keep the largest island of the threshold above air; scissors through the 3D
// view (a freehand outline). Prints the figures (median of 3); asserts nothing about time.
#include <QTest>

#include <algorithm>
#include <chrono>
#include <functional>

#include "core/io/Catalog.h"
#include "core/scene/ViewFrame.h"
#include "core/segmentation/GrowFromSeeds.h"
#include "core/segmentation/ScissorsCut.h"
#include "core/segmentation/SegmentEffects.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

constexpr const char* kHeadCt = "dcm_qa_ct/Philips_S21570/S2020";

void stroke(SegmentMask& mask, glm::ivec3 a, glm::ivec3 b) {
    const glm::ivec3 d = b - a;
    const int n = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z), 1});
    for (int s = 0; s <= n; ++s) {
        const glm::ivec3 v(glm::round(glm::dvec3(a) + glm::dvec3(d) * (double(s) / n)));
        mask.set(mask.linearIndex(v.x, v.y, v.z));
    }
}

double medianMs(int runs, const std::function<void()>& work) {
    std::vector<double> ms;
    for (int r = 0; r < runs; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        work();
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count());
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

} // namespace

class BenchSegmentation : public QObject {
    Q_OBJECT
    Volume ct_;

private slots:
    void initTestCase() {
        REQUIRE_DATA(kHeadCt);
        ct_ = loadPath(test::kRealData / kHeadCt);
    }

    void growFromSeeds() {
        std::vector<SegmentMask> seeds(3, SegmentMask(ct_.dims()));
        for (const int k : {50, 70, 90}) {
            stroke(seeds[0], {256, k == 90 ? 55 : 40, k}, {256, k == 90 ? 60 : 47, k});
            stroke(seeds[1], {150, 200, k}, {300, 200, k});
            stroke(seeds[2], {30, 200, k}, {90, 200, k});
        }
        stroke(seeds[0], {108, 200, 70}, {111, 200, 70});
        stroke(seeds[0], {382, 200, 70}, {385, 200, 70});
        stroke(seeds[0], {256, 422, 70}, {256, 431, 70});
        std::vector<SegmentMask> more = seeds;
        stroke(more[1], {200, 150, 80}, {300, 300, 80});
        for (const double margin : {0.0, 5.0}) {
            GrowOutcome first, update;
            std::size_t box = 0;
            const double firstMs = medianMs(3, [&] {
                SeedGrower grower(ct_, GrowOptions{margin});
                first = grower.grow(seeds);
                box = grower.box().voxelCount();
            });
            std::vector<double> updates;
            for (int run = 0; run < 3; ++run) {
                SeedGrower grower(ct_, GrowOptions{margin});
                grower.grow(seeds);
                updates.push_back(medianMs(1, [&] {
                    update = grower.grow(more);
                    grower.masks();
                }));
            }
            std::sort(updates.begin(), updates.end());
            qInfo("grow_from_seeds margin=%.0fmm box=%zu voxels: first_ms=%.0f (grow %.0f, "
                  "%zu settled) update_ms=%.0f (grow %.0f, %zu settled, incremental %d)",
                  margin, box, firstMs, first.ms, first.voxelsSettled, updates[1], update.ms,
                  update.voxelsSettled, int(update.incremental));
        }
    }

    void marginAndIslands() {
        const SegmentMask bone = thresholdMask(ct_, 300.0, 4000.0);
        const double marginMs = medianMs(3, [&] { marginMask(bone, ct_.geometry(), 5.0); });
        const double shrinkMs = medianMs(3, [&] { marginMask(bone, ct_.geometry(), -5.0); });
        const SegmentMask body = thresholdMask(ct_, -500.0, 4000.0);
        const double islandsMs = medianMs(3, [&] { keepLargestIsland(body); });
        qInfo("margin_5mm_ms=%.0f shrink_5mm_ms=%.0f (bone, %zu voxels); keep_largest_ms=%.0f "
              "(above -500 HU, %zu voxels, %zu islands)",
              marginMs, shrinkMs, bone.count(), islandsMs, body.count(), islandsOf(body).size());
    }

    void scissors() {
        const int w = 800, h = 600;
        const ViewFrame f = makeViewFrame(ct_.geometry(), Camera{}, w, h);
        std::vector<glm::dvec2> outline;
        for (int n = 0; n < 400; ++n) { // a wobbly freehand loop of 400 points
            const double a = 2.0 * 3.14159265358979 * n / 400.0;
            outline.emplace_back(400.0 + (150.0 + 20.0 * std::sin(9.0 * a)) * std::cos(a),
                                 300.0 + (120.0 + 15.0 * std::cos(7.0 * a)) * std::sin(a));
        }
        const ScreenShape shape = ScreenShape::polygon(outline);
        std::size_t cut = 0;
        const double ms = medianMs(3, [&] {
            cut = scissorsMask(ct_.geometry(), imageProjection(f), glm::dvec2(w, h), shape,
                               ScissorsSide::Inside)
                      .count();
        });
        qInfo("scissors_polygon_ms=%.0f (400 points, %zu voxels inside)", ms, cut);
    }
};

QTEST_APPLESS_MAIN(BenchSegmentation)
#include "bench_segmentation.moc"
