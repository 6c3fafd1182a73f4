// The GPU ray caster's part mode: a volume drawn in parts (each part a
// GpuRayCaster over its box plus halo), composited front to back, equals the
// GPU ray caster's image of the whole volume; the parts take each sample once.
#include <QTest>

#include "core/image/ImageMetrics.h"
#include "render/GpuRayCaster.h"
#include "render/OffscreenContext.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/core/raycast/VolumeParts.h"

using namespace lucent;
using namespace lucent::test;

namespace {

std::unique_ptr<Renderer> openGpu(const Volume& part, const VolumePart& where) {
    return std::make_unique<GpuRayCaster>(part, where);
}

} // namespace

class TestGpuVolumeParts : public QObject {
    Q_OBJECT

    std::unique_ptr<OffscreenContext> context_;
    Volume volume_ = facesAndBlobs(VoxelType::Int16);

private slots:
    void initTestCase() { context_ = OffscreenContext::create(); }

    void partsEqualTheWhole_data() {
        QTest::addColumn<int>("scene");
        QTest::newRow("linear shaded") << 0;
        QTest::newRow("cubic shaded") << 1;
        QTest::newRow("preintegrated") << 2;
        QTest::newRow("iso") << 3;
        QTest::newRow("mip") << 4;
        QTest::newRow("minip") << 5;
        QTest::newRow("average") << 6;
    }
    void partsEqualTheWhole() {
        QFETCH(int, scene);
        RenderDescription d = describe(volume_, rampTf(true), 48);
        d.background = glm::dvec3(0.1, 0.2, 0.3);
        d.sampling.brickSize = 16;
        if (scene == 1) {
            d.sampling.interpolation = Interpolation::Cubic;
        } else if (scene == 2) {
            d.sampling.preintegrate = true;
        } else if (scene == 3) {
            d.mode = RenderMode::Isosurface;
            d.isoValue = 100.0;
        } else if (scene >= 4) {
            const RenderMode modes[] = {RenderMode::Mip, RenderMode::MinIp, RenderMode::Average};
            d.mode = modes[scene - 4];
            d.transferFunction = rampTf(false);
        }
        GpuRayCaster whole(volume_);
        for (int parts : {2, 3, 4}) {
            compareInViews(
                whole, volume_, split(volume_, parts, d, 8), d, openGpu,
                [&](const View& view, const RenderResult& reference, const Composite& c) {
                    const double db = psnr(reference.image, c.image);
                    QVERIFY2(db >= 50.0,
                             qPrintable(
                                 QString("%1 parts, %2: %3 dB").arg(parts).arg(view.name).arg(db)));
                });
        }
    }

    void everySampleIsTakenOnce() {
        RenderDescription d = describe(volume_, flatTf(0.01), 49);
        d.sampling.earlyTermination = 1.0;
        d.sampling.emptySpaceLeaping = false;
        d.sampling.step = 0.5;
        d.sampling.brickSize = 16;
        GpuRayCaster whole(volume_);
        for (int parts : {2, 3, 4}) {
            expectEverySampleOnce(whole, volume_, split(volume_, parts, d, 8), d, openGpu);
        }
    }

    // A clip box that leaves one part nothing to draw: that part's image is
    // empty and the composite still equals the whole.
    void aClipBoxEmptiesOnePart() {
        RenderDescription d = describe(volume_, rampTf(true), 48);
        d.sampling.brickSize = 16;
        const Parts p = split(volume_, 3, d, 8);
        clipAwayPart(d, p, 2, volume_.dims());
        GpuRayCaster whole(volume_);
        expectPartEmptied(whole, volume_, p, d, 2, openGpu);
    }

    // GL ranks ask for the EGL device of their local rank; any index gives a
    // context (modulo the devices there are, or the next display that works).
    void aContextForEveryDeviceIndex() {
        for (int device : {0, 1, 2, 3, 17}) {
            const auto context = OffscreenContext::create(device);
            QVERIFY(!context->description().empty());
        }
        context_->makeCurrent();
    }
};

QTEST_GUILESS_MAIN(TestGpuVolumeParts)
#include "test_gpu_volume_parts.moc"
