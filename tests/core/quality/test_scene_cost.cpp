// What a scene would cost brute force, against what the renderer took.
#include <QTest>

#include "core/quality/SceneCost.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/core/raycast/RaycastScenes.h"

using namespace lucent;

class TestSceneCost : public QObject {
    Q_OBJECT
private slots:
    // Without leaping and early termination the ray caster takes every lattice
    // sample: exactly the brute-force count, clip box and camera included.
    void bruteForceIsWhatAPlainMarchTakes() {
        const Volume v = test::makeVolume({30, 26, 22}, test::blobs, VoxelType::Int16);
        for (const double azimuth : {0.0, 35.0}) {
            // Faint enough that no ray saturates (a float sum reaches 1 exactly).
            RenderDescription d = test::describe(v, test::flatTf(0.001), 40);
            d.camera.azimuth = azimuth;
            d.camera.elevation = 10.0;
            d.clip.lo = {2.5, 0, 3};
            d.sampling.emptySpaceLeaping = false;
            d.sampling.earlyTermination = 1.0;
            const std::size_t brute = bruteForceSamples(d);
            QVERIFY(brute > 1000);
            QCOMPARE(CpuRayCaster(v).render(d).stats.samples, brute);
            RenderDescription leapt = d;
            leapt.transferFunction = test::rampTf(true);
            leapt.sampling.emptySpaceLeaping = true;
            leapt.sampling.earlyTermination = 0.99;
            QVERIFY(CpuRayCaster(v).render(leapt).stats.samples < brute / 2);
            d.sampling.step = 0.25;
            QVERIFY(bruteForceSamples(d) >
                    brute * 19 / 10); // half the step, about twice the samples
        }
    }
};

QTEST_GUILESS_MAIN(TestSceneCost)
#include "test_scene_cost.moc"
