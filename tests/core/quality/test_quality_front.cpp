// The speed/accuracy front, without a renderer: the sweep's settings, which
// points are on the front, and the choice within a time budget.
#include <QTest>

#include "core/quality/QualityFront.h"

using namespace lucent;

namespace {

QualityPoint point(double ms, double db, bool shading = true) {
    QualityPoint p;
    p.ms = ms;
    p.psnrDb = db;
    p.setting.shading = shading;
    return p;
}

} // namespace

class TestQualityFront : public QObject {
    Q_OBJECT
private slots:
    void sweepCoversEveryCombination() {
        const auto sweep = qualitySweep({2, 1, 0.5, 0.25, 0.125}, {32, 64});
        // Per step and brick: nearest (post, preintegrated), linear (3), cubic (2); x2 shading.
        QCOMPARE(sweep.size(), std::size_t(5 * 2 * 7 * 2));
        const auto pre = std::count_if(sweep.begin(), sweep.end(), [](const QualitySetting& s) {
            return s.classification == Classification::Pre;
        });
        QCOMPARE(pre, std::ptrdiff_t(5 * 2 * 2));
        QCOMPARE(sweep.front().classificationName(), std::string("post"));
        RenderDescription d;
        QualitySetting s;
        s.step = 0.25;
        s.preintegrate = true;
        s.shading = false;
        s.brickSize = 32;
        const RenderDescription applied = s.applyTo(d);
        QCOMPARE(applied.sampling.step, 0.25);
        QVERIFY(applied.sampling.preintegrate);
        QVERIFY(!applied.transferFunction.shading.enabled);
        QCOMPARE(applied.sampling.brickSize, 32);
        const RenderDescription ref = qualityReference(d);
        QCOMPARE(ref.sampling.step, 1.0 / 16.0);
        QCOMPARE(ref.sampling.earlyTermination, 1.0);
        QVERIFY(ref.sampling.precision == Precision::Double);
        QVERIFY(ref.sampling.interpolation == Interpolation::Cubic);
    }

    void frontKeepsWhatNothingBeats() {
        std::vector<QualityPoint> pts = {point(10, 30),      point(20, 35), point(15, 29),
                                         point(40, 35),      point(50, 45), point(50, 45),
                                         point(1, 60, false)};
        markParetoFront(pts);
        QVERIFY(pts[0].pareto);
        QVERIFY(pts[1].pareto);
        QVERIFY(!pts[2].pareto);                 // slower and worse than the first
        QVERIFY(!pts[3].pareto);                 // as good as the second, slower
        QVERIFY(pts[4].pareto && pts[5].pareto); // ties keep both
        QVERIFY(pts[6].pareto); // unshaded: its own front, does not dominate the shaded ones
    }

    void choiceWithinATimeBudget() {
        std::vector<QualityPoint> pts = {point(10, 30), point(20, 35), point(50, 45),
                                         point(5, 50, false)};
        markParetoFront(pts);
        QCOMPARE(bestWithin(pts, 25, true)->psnrDb, 35.0);
        QCOMPARE(bestWithin(pts, 1000, true)->psnrDb, 45.0);
        QCOMPARE(bestWithin(pts, 1, true)->ms, 10.0); // none that fast: the fastest
        QCOMPARE(bestWithin(pts, 25, false)->psnrDb, 50.0);
        QVERIFY(!bestWithin({}, 10, true));
    }
};

QTEST_GUILESS_MAIN(TestQualityFront)
#include "test_quality_front.moc"
