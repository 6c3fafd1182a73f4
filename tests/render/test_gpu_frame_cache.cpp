// What a GPU frame keeps from the last (render/BrickStreamer.h): the cell
// masks, boxes, level choice and page table depend on the transfer function,
// clip box, budget and levels, not on the camera. A drag rebuilds none of them
// (counted); every change they depend on rebuilds them, and the frame then
// equals a fresh caster's, pixel for pixel.
#include <QTest>

#include "tests/core/raycast/RaycastScenes.h"
#include "tests/render/GlTestSupport.h"
#include "tests/render/RealOrMadeCt.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSize = 96;

// The frame `kept` drew, against a caster that never saw another description:
// equal but for rounding (the atlas may place boxes elsewhere).
void expectAsFresh(const Volume& v, const GpuRenderResult& kept, const RenderDescription& d,
                   const GpuOptions& options, const std::string& name) {
    GpuRayCaster fresh(v, options);
    const GpuRenderResult f = fresh.renderWithGpuStats(d);
    const double p = comparedPsnr(kept.frame.image, f.frame.image, "frame_cache_" + name, 60.0);
    QVERIFY2(
        p >= 60.0,
        qPrintable(
            QString("%1: %2 dB against a fresh caster").arg(QString::fromStdString(name)).arg(p)));
    QCOMPARE(kept.frame.stats.bricksUsed, f.frame.stats.bricksUsed);
    QCOMPARE(kept.frame.stats.lod, f.frame.stats.lod);
}

void expectRebuilt(const GpuRenderResult& r, const char* what) {
    QVERIFY2(r.gpu.bricksPlanned, qPrintable(QString("%1: the bricks were not planned").arg(what)));
}

} // namespace

class TestGpuFrameCache : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;

private slots:
    void initTestCase() { context_ = OffscreenContext::create(); }

    // A drag: 12 frames turning and zooming rebuild nothing and upload nothing.
    void cameraMoveRebuildsNothing() {
        const Volume v = realOrMade();
        GpuRayCaster gpu(v);
        RenderDescription d = describe(v, loadPreset("ct-bone"), kSize);
        const GpuRenderResult first = gpu.renderWithGpuStats(d);
        QVERIFY(first.gpu.bricksPlanned);
        QVERIFY(first.gpu.levelsClassified > 0);
        QVERIFY(first.gpu.tableUploaded);
        int planned = 0, classified = 0, tables = 0;
        std::size_t uploaded = 0;
        GpuRenderResult last;
        for (int frame = 1; frame <= 12; ++frame) {
            d.camera.azimuth = 4.0 * frame;
            d.camera.elevation = 2.0 * frame;
            last = gpu.renderWithGpuStats(d);
            planned += last.gpu.bricksPlanned ? 1 : 0;
            classified += last.gpu.levelsClassified;
            tables += last.gpu.tableUploaded ? 1 : 0;
            uploaded += last.gpu.bytesUploaded;
        }
        QCOMPARE(planned, 0);
        QCOMPARE(classified, 0);
        QCOMPARE(tables, 0);
        QCOMPARE(uploaded, std::size_t(0));
        QCOMPARE(last.frame.stats.bricksUsed, first.frame.stats.bricksUsed);
        expectAsFresh(v, last, d, {}, "camera");
    }

    // Zoomed in, other pages leave the view: the plan follows them.
    void pagesLeavingTheViewReplan() {
        const Volume v = realOrMade();
        GpuRayCaster gpu(v);
        RenderDescription d = describe(v, loadPreset("ct-bone"), kSize);
        gpu.renderWithGpuStats(d);
        d.camera.zoom = 4.0;
        d.camera.azimuth = 20.0;
        const GpuRenderResult zoomed = gpu.renderWithGpuStats(d);
        expectRebuilt(zoomed, "zoomed in");
        QCOMPARE(zoomed.gpu.levelsClassified, 0); // the masks hold: only the view changed
        expectAsFresh(v, zoomed, d, {}, "zoomed");
    }

    void transferFunctionChangeRebuilds_data() {
        QTest::addColumn<QString>("change");
        QTest::newRow("opacity") << "opacity";
        QTest::newRow("colour") << "colour";
        QTest::newRow("preset") << "preset";
        QTest::newRow("iso") << "iso";
    }
    void transferFunctionChangeRebuilds() {
        QFETCH(QString, change);
        const Volume v = realOrMade();
        GpuRayCaster gpu(v);
        RenderDescription d = describe(v, loadPreset("ct-bone"), kSize);
        if (change == "iso") {
            d.mode = RenderMode::Isosurface;
            d.isoValue = 300.0;
        }
        const GpuRenderResult before = gpu.renderWithGpuStats(d);
        d.camera.azimuth = 10.0;
        gpu.renderWithGpuStats(d); // kept
        if (change == "opacity") {
            for (OpacityPoint& p : d.transferFunction.opacity) {
                p.value -= 150.0; // bone's ramp starts lower: more shows
            }
        } else if (change == "colour") {
            for (ColourPoint& c : d.transferFunction.colour) {
                c.rgb = glm::dvec3(1.0) - c.rgb;
            }
        } else if (change == "preset") {
            d.transferFunction = loadPreset("ct-soft-tissue");
        } else {
            d.isoValue = 900.0;
        }
        const GpuRenderResult after = gpu.renderWithGpuStats(d);
        if (change == "colour") {
            // The same values show: masks and bricks hold, the tables change.
            QCOMPARE(after.gpu.levelsClassified, 0);
        } else {
            QVERIFY(after.gpu.levelsClassified > 0);
            expectRebuilt(after, qPrintable(change));
        }
        QVERIFY(psnr(after.frame.image, before.frame.image) < 40.0);
        expectAsFresh(v, after, d, {}, change.toStdString());
    }

    void clipChangeRebuilds() {
        const Volume v = realOrMade();
        GpuRayCaster gpu(v);
        RenderDescription d = describe(v, loadPreset("ct-bone"), kSize);
        gpu.renderWithGpuStats(d);
        const glm::dvec3 hi(v.dims() - 1);
        d.clip.lo = glm::dvec3(0.0);
        d.clip.hi = glm::dvec3(hi.x * 0.6, hi.y, hi.z * 0.7);
        const GpuRenderResult clipped = gpu.renderWithGpuStats(d);
        QVERIFY(clipped.gpu.levelsClassified > 0);
        expectRebuilt(clipped, "clip");
        expectAsFresh(v, clipped, d, {}, "clip");
        d.clip = ClipBox{}; // and back: the whole volume again
        const GpuRenderResult whole = gpu.renderWithGpuStats(d);
        expectRebuilt(whole, "clip removed");
        expectAsFresh(v, whole, d, {}, "unclipped");
    }

    // Under a budget too small for level 0, the levels follow the camera:
    // every frame plans again (the masks are kept), and a zoom refines.
    void levelsFollowTheCameraUnderABudget() {
        const Volume v = realOrMade();
        GpuOptions small;
        small.budgetBytes = v.byteCount() / 3;
        GpuRayCaster gpu(v, small);
        RenderDescription d = describe(v, loadPreset("ct-bone"), kSize);
        const GpuRenderResult far = gpu.renderWithGpuStats(d);
        QVERIFY(far.frame.stats.lod > 0);
        d.camera.zoom = 3.0;
        const GpuRenderResult near = gpu.renderWithGpuStats(d);
        expectRebuilt(near, "zoomed under a budget");
        QVERIFY(near.gpu.levelOfBrick != far.gpu.levelOfBrick);
        expectAsFresh(v, near, d, small, "budget_zoom");
    }

    // The level a sampling setting asks for changes the bricks: a brick
    // size, tricubic coefficients, pre-integration (neighbouring cells).
    void samplingChangeRebuilds_data() {
        QTest::addColumn<QString>("change");
        QTest::newRow("brick-size") << "brick-size";
        QTest::newRow("cubic") << "cubic";
        QTest::newRow("preintegration") << "preintegration";
    }
    void samplingChangeRebuilds() {
        QFETCH(QString, change);
        const Volume v = realOrMade();
        GpuRayCaster gpu(v);
        RenderDescription d = describe(v, loadPreset("ct-bone"), kSize);
        gpu.renderWithGpuStats(d);
        if (change == "brick-size") {
            d.sampling.brickSize = 16;
        } else if (change == "cubic") {
            d.sampling.interpolation = Interpolation::Cubic;
        } else {
            d.sampling.preintegrate = true;
        }
        const GpuRenderResult after = gpu.renderWithGpuStats(d);
        expectRebuilt(after, qPrintable(change));
        QVERIFY(after.gpu.levelsClassified > 0);
        expectAsFresh(v, after, d, {}, change.toStdString());
    }
};

QTEST_GUILESS_MAIN(TestGpuFrameCache)
#include "test_gpu_frame_cache.moc"
