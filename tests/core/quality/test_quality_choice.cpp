// Quality chosen from a front: levels and target times parsed, the most
// accurate front point within the (scaled) time, the fastest with a message
// when none fits, the default with a message without a front, the drag step
// from the same filter, the cached front read back as written, and its key
// following the opacity curve (real CT), not the colours.
#include <QTemporaryDir>
#include <QTest>

#include <fstream>
#include <limits>

#include "core/io/Catalog.h"
#include "core/quality/MeasuredFront.h"
#include "core/quality/QualityChoice.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/core/raycast/RaycastScenes.h"

using namespace lucent;

namespace {

QualityPoint point(double step, Interpolation interp, double ms, double db, bool shading = true) {
    QualityPoint p;
    p.setting.step = step;
    p.setting.interpolation = interp;
    p.setting.shading = shading;
    p.ms = ms;
    p.psnrDb = db;
    p.samples = std::size_t(1000 / step);
    p.ssim = 0.9;
    return p;
}

// A front as measured: linear is fast, cubic accurate; one dominated point.
std::vector<QualityPoint> front() {
    std::vector<QualityPoint> pts = {
        point(2, Interpolation::Linear, 10, 33),    point(1, Interpolation::Linear, 20, 36),
        point(0.5, Interpolation::Linear, 40, 38),  point(2, Interpolation::Nearest, 30, 30),
        point(1, Interpolation::Cubic, 100, 45),    point(0.5, Interpolation::Cubic, 200, 52),
        point(0.25, Interpolation::Cubic, 400, 55), point(1, Interpolation::Linear, 5, 40, false),
    };
    markParetoFront(pts);
    return pts;
}

} // namespace

class TestQualityChoice : public QObject {
    Q_OBJECT
private slots:
    void levelsAndTimesParse() {
        QCOMPARE(parseQualityRequest("fast").budgetMs, kFastBudgetMs);
        QCOMPARE(parseQualityRequest("balanced").budgetMs, kBalancedBudgetMs);
        QCOMPARE(parseQualityRequest("best").budgetMs, kBestBudgetMs);
        QVERIFY(kFastBudgetMs < kBalancedBudgetMs && kBalancedBudgetMs < kBestBudgetMs);
        QCOMPARE(parseQualityRequest("120ms").budgetMs, 120.0);
        QCOMPARE(parseQualityRequest("7.5").budgetMs, 7.5);
        for (const char* bad : {"", "ms", "quick", "-5ms", "0ms", "12 ms", "nanms", "infms"}) {
            try {
                parseQualityRequest(bad);
                QFAIL(qPrintable(QString("accepted '%1'").arg(bad)));
            } catch (const std::invalid_argument& e) {
                QVERIFY2(QString(e.what()).contains(QString("'%1'").arg(bad)), e.what());
            }
        }
    }

    void mostAccurateWithinTheBudget() {
        const auto pts = front();
        QVERIFY(!pts[3].pareto); // nearest: slower and worse than linear step 1
        QualityChoice c = chooseQuality(pts, 50, true);
        QVERIFY(c.fromFront && c.withinBudget && c.message.empty());
        QCOMPARE(c.setting.step, 0.5);
        QVERIFY(c.setting.interpolation == Interpolation::Linear);
        QCOMPARE(c.psnrDb, 38.0);
        c = chooseQuality(pts, 250, true);
        QVERIFY(c.setting.interpolation == Interpolation::Cubic);
        QCOMPARE(c.setting.step, 0.5);
        QCOMPARE(chooseQuality(pts, 1e9, true).psnrDb, 55.0);
        // Times scale with the pixels: four times the pixels, a quarter of the budget.
        c = chooseQuality(pts, 250, true, {4.0});
        QCOMPARE(c.psnrDb, 38.0);
        QCOMPARE(c.predictedMs, 160.0);
        // A fixed part of each frame does not grow with the pixels.
        QCOMPARE(chooseQuality(pts, 130, true, {4.0}).psnrDb, 36.0); // linear 0.5: 160 ms
        c = chooseQuality(pts, 130, true, {4.0, 10.0});              // 10 + 30 * 4
        QCOMPARE(c.psnrDb, 38.0);
        QCOMPARE(c.predictedMs, 130.0);
        QCOMPARE((TimeModel{4.0, 50.0}.predict(20.0)), 20.0); // never more than the time itself
        // The other shading has its own front.
        c = chooseQuality(pts, 50, false);
        QVERIFY(!c.setting.shading);
        QCOMPARE(c.psnrDb, 40.0);
    }

    void unreachableBudgetGivesTheFastestWithAMessage() {
        const auto pts = front();
        for (const double budget : {0.0, 5.0, -1.0}) {
            const QualityChoice c = chooseQuality(pts, budget, true);
            QVERIFY(c.fromFront);
            QVERIFY(!c.withinBudget);
            QCOMPARE(c.predictedMs, 10.0);
            QCOMPARE(c.setting.step, 2.0);
            QVERIFY2(QString::fromStdString(c.message).contains("fastest"), c.message.c_str());
        }
    }

    void noFrontGivesTheDefaultWithAMessage() {
        for (const auto& pts : {std::vector<QualityPoint>{}, front()}) {
            // front() has one unshaded point only; empty has none at all.
            const bool shading = pts.empty();
            QualityChoice c = chooseQuality(pts, 100, shading);
            if (!pts.empty()) {
                c = chooseQuality({pts.begin(), pts.begin() + 3}, 100, false);
            }
            QVERIFY(!c.fromFront);
            QVERIFY(!c.withinBudget);
            QVERIFY2(QString::fromStdString(c.message).contains("no measured front"),
                     c.message.c_str());
            QCOMPARE(c.setting.step, QualitySetting{}.step);
            QVERIFY(QString::fromStdString(describeChoice(c)).contains("not measured"));
        }
    }

    void dragUsesACoarserStepOfTheSameFilter() {
        const auto pts = front();
        QualitySetting still = chooseQuality(pts, 250, true).setting; // cubic 0.5
        // A quarter of the pixels while dragging: cubic 1 (100 ms) fits 30 ms * 4.
        InteractiveQuality q = chooseInteractive(pts, still, 30, {}, 2);
        QCOMPARE(q.imageScale, 0.5);
        QCOMPARE(q.stepFactor, 2.0);
        // Nothing fits: the coarsest step of that filter.
        q = chooseInteractive(pts, still, 1, {}, 2);
        QCOMPARE(q.stepFactor, 2.0);
        // Everything fits: the still step itself.
        q = chooseInteractive(pts, still, 1e9, {}, 2);
        QCOMPARE(q.stepFactor, 1.0);
        still = chooseQuality(pts, 50, true).setting; // linear 0.5
        q = chooseInteractive(pts, still, 3, {}, 2);  // linear 2 (10 ms / 4)
        // A fixed 8 ms a frame does not shrink with the drag image: nothing fits 3 ms.
        QCOMPARE(chooseInteractive(pts, still, 3, {1.0, 8.0}, 2).stepFactor, 4.0);
        // linear 1: 8 + 12 / 4 = 11 ms fits 12; linear 0.5: 8 + 32 / 4 = 16 does not.
        QCOMPARE(chooseInteractive(pts, still, 12, {1.0, 8.0}, 2).stepFactor, 2.0);
        QCOMPARE(q.stepFactor, 4.0);
        QCOMPARE(chooseInteractive({}, still, 3, {}, 2).stepFactor, 2.0);
    }

    // The quick front with the real CPU ray caster on a small volume: every
    // setting of the quick sweep, one shading, a front, a fixed part no longer
    // than the fastest frame, and a choice that is one of its points.
    void quickFrontIsMeasured() {
        const Volume v = test::makeVolume({30, 26, 22}, test::blobs, VoxelType::Int16);
        RenderDescription d = test::describe(v, test::rampTf(true), 64);
        d.width = 96; // the quick size keeps the aspect
        CpuRayCaster cpu(v);
        std::size_t calls = 0;
        const MeasuredFront f = measureQuickFront(
            d, "cpu", [&](const RenderDescription& r) { return cpu.render(r); },
            [&](const RenderDescription& r) { return cpu.render(r); },
            [&](std::size_t done, std::size_t total) {
                QCOMPARE(done, ++calls);
                QCOMPARE(total, quickSweep(true).size());
            });
        QCOMPARE(calls, quickSweep(true).size());
        QCOMPARE(f.key, frontKey(d, "cpu"));
        QCOMPARE(f.width, kQuickFrontSize);
        QCOMPARE(f.height, int(std::lround(kQuickFrontSize * 64.0 / 96.0)));
        QCOMPARE(f.points.size(), quickSweep(true).size());
        double fastest = 1e300;
        for (const QualityPoint& p : f.points) {
            QVERIFY(p.setting.shading);
            QVERIFY(p.ms > 0.0 && p.samples > 0 && p.psnrDb > 10.0);
            fastest = std::min(fastest, p.ms);
        }
        QVERIFY(f.fixedMs >= 0.0 && f.fixedMs <= fastest);
        // Cubic at step 0.25 is nearest the reference (tricubic, step 1/16).
        const auto best = std::max_element(
            f.points.begin(), f.points.end(),
            [](const QualityPoint& a, const QualityPoint& b) { return a.psnrDb < b.psnrDb; });
        QVERIFY(best->setting.interpolation == Interpolation::Cubic);
        QVERIFY(best->pareto);
        const QualityChoice c = chooseQuality(f.points, 1e9, true, f.timeModel(96, 64));
        QCOMPARE(c.psnrDb, best->psnrDb);
    }

    void cachedFrontReadsBackAsWritten() {
        QTemporaryDir dir;
        const Volume v = test::makeVolume(
            {12, 10, 8}, [](int i, int j, int k) { return double(i * j - k); }, VoxelType::Int16);
        RenderDescription d;
        d.volume = &v;
        MeasuredFront f;
        f.key = frontKey(d, "cpu");
        f.width = 128;
        f.height = 96;
        f.fixedMs = 1.5;
        f.points = front();
        const std::filesystem::path cache = dir.filePath("cache/lucent").toStdString();
        QVERIFY(!loadFront(cache, f.key));
        saveFront(cache, f);
        const auto back = loadFront(cache, f.key);
        QVERIFY(back);
        QCOMPARE(back->width, 128);
        QCOMPARE(back->fixedMs, 1.5);
        QCOMPARE(back->points.size(), f.points.size());
        for (std::size_t n = 0; n < f.points.size(); ++n) {
            QCOMPARE(back->points[n].setting.step, f.points[n].setting.step);
            QVERIFY(back->points[n].setting.interpolation == f.points[n].setting.interpolation);
            QCOMPARE(back->points[n].pareto, f.points[n].pareto);
            QCOMPARE(back->points[n].psnrDb, f.points[n].psnrDb);
        }
        QCOMPARE(back->timeScale(256, 192), 4.0);
        // Another backend, shading or volume: another key, no front.
        QVERIFY(frontKey(d, "gl") != f.key);
        d.transferFunction.shading.enabled = !d.transferFunction.shading.enabled;
        QVERIFY(frontKey(d, "cpu") != f.key);
        d.transferFunction.shading.enabled = !d.transferFunction.shading.enabled;
        d.sampling.precision = Precision::Double;
        QVERIFY(frontKey(d, "cpu") != f.key);
        d.sampling.precision = Precision::Float;
        QCOMPARE(frontKey(d, "cpu"), f.key);
        d.transferFunction.shading.enabled = !d.transferFunction.shading.enabled;
        Volume w = test::makeVolume(
            {12, 10, 8}, [](int i, int j, int k) { return double(i * j - k); }, VoxelType::Int16);
        w.voxels<std::int16_t>()[0] = 999;
        d.volume = &w;
        d.transferFunction.shading.enabled = !d.transferFunction.shading.enabled;
        QVERIFY(frontKey(d, "cpu") != f.key);
        // A damaged file is measured again, not trusted.
        std::ofstream(frontCachePath(cache, f.key), std::ios::app) << "1,linear,post,1,64,x\n";
        QVERIFY(!loadFront(cache, f.key));
    }

    void opacityShapeSeesTheWholeValueRange() {
        // 256 x 256 x 64: a step of count/65536 through the linear index would
        // see only the column x = 0 (all 0 here), and a 0.5 shift would matter.
        const Volume wide = test::makeVolume(
            {256, 256, 64}, [](int i, int, int) { return i == 0 ? 0.0 : 1000.0 * (i % 2); },
            VoxelType::Int16);
        TransferFunction a;
        a.opacity = {{100.0, 0.0}, {200.0, 0.5}};
        a.colour = {{0.0, glm::dvec3(1.0)}};
        TransferFunction shifted = a;
        for (OpacityPoint& p : shifted.opacity) {
            p.value += 0.5;
        }
        QCOMPARE(opacityShape(shifted, wide), opacityShape(a, wide));
        TransferFunction later = a;
        for (OpacityPoint& p : later.opacity) {
            p.value += 500.0;
        }
        QVERIFY(opacityShape(later, wide) != opacityShape(a, wide));

        // Non-finite voxels are left out of the range, so the curves still differ.
        Volume odd = test::makeVolume(
            {8, 8, 8}, [](int i, int j, int k) { return 16.0 * (i + 8 * j + 64 * k) / 8.0; },
            VoxelType::Float32);
        odd.voxels<float>()[0] = std::numeric_limits<float>::quiet_NaN();
        odd.voxels<float>()[1] = std::numeric_limits<float>::infinity();
        QVERIFY(opacityShape(later, odd) != opacityShape(a, odd));
        Volume huge = test::makeVolume(
            {4, 4, 4}, [](int i, int, int) { return i % 2 == 0 ? -1e38 : 1e38; },
            VoxelType::Float32);
        QVERIFY(!opacityShape(a, huge).empty());
    }

    void frontKeyFollowsTheOpacityCurve() {
        const std::filesystem::path series =
            std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2010";
        if (!std::filesystem::exists(series)) {
            QSKIP("real test data not found (see ../shared/data/README.md)");
        }
        const Volume ct = loadPath(series);
        RenderDescription d;
        d.volume = &ct;
        d.transferFunction = loadPreset("ct-bone");
        const std::string bone = frontKey(d, "cpu");
        // Each preset its own front.
        for (const char* other : {"ct-soft-tissue", "ct-angio", "ct-lung"}) {
            d.transferFunction = loadPreset(other);
            QVERIFY2(frontKey(d, "cpu") != bone, other);
        }
        // The colours decide neither time nor step: the same front.
        d.transferFunction = loadPreset("ct-bone");
        for (ColourPoint& c : d.transferFunction.colour) {
            c.rgb.r = 1.0 - c.rgb.r;
        }
        QCOMPARE(frontKey(d, "cpu"), bone);
        // The ramp 300 HU later, or twice as opaque: another front.
        TransferFunction later = loadPreset("ct-bone");
        for (OpacityPoint& p : later.opacity) {
            p.value += 300.0;
        }
        d.transferFunction = later;
        QVERIFY(frontKey(d, "cpu") != bone);
        TransferFunction denser = loadPreset("ct-bone");
        for (OpacityPoint& p : denser.opacity) {
            p.opacity = std::min(1.0, 2.0 * p.opacity);
        }
        d.transferFunction = denser;
        QVERIFY(frontKey(d, "cpu") != bone);
        // MIP does not look at the opacities.
        d.mode = RenderMode::Mip;
        const std::string mip = frontKey(d, "cpu");
        d.transferFunction = loadPreset("ct-bone");
        QCOMPARE(frontKey(d, "cpu"), mip);
    }
};

QTEST_GUILESS_MAIN(TestQualityChoice)
#include "test_quality_choice.moc"
