// The render server's frames drawn in this process on the CPU (no GL): once
// the render thread hands an encoded image back, the next frame of its size is
// drawn into its buffers and equals a fresh caster's; an image not handed
// back, or one of another size, leaves the next frame with new buffers.
#include <QTest>

#include <memory>
#include <string>

#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/tf/TransferFunction.h"
#include "server/LocalFrameSource.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/support/RealData.h"

using namespace lucent;
using namespace lucent::test;

namespace {

const char* const kCt = "dcm_qa_ct/Philips_S21570/S2010";

std::string frameBuffers(const remote::LocalFrameSource& source,
                         const std::shared_ptr<const SeriesEntry>& entry) {
    return frameDetail(source.lastFrameDetails(entry), "frame_buffers").value_or("(none)");
}

} // namespace

class TestLocalFrameSource : public QObject {
    Q_OBJECT

private slots:
    void encodedImagesDrawTheNextFrame() {
        REQUIRE_DATA(kCt);
        const auto entry =
            std::make_shared<const SeriesEntry>(scanPath(kRealData / kCt).series.front());
        const Volume volume = loadSeries(*entry);
        remote::LocalFrameSource source(RendererKind::Cpu);
        QVERIFY(source.start().startsWith("cpu"));
        QVERIFY(source.lastFrameDetails(entry).empty()); // not loaded yet
        RenderDescription d = describe(volume, loadPreset("ct-bone"), 96);
        d.volume = nullptr; // the source renders its own copy of the series

        const auto expect = [&](const RenderDescription& frame) {
            RenderDescription own = frame;
            own.volume = &volume;
            return CpuRayCaster(volume).render(own).image;
        };
        ImageRGBA8 image = source.render(entry, d);
        QVERIFY(image == expect(d));
        QCOMPARE(frameBuffers(source, entry), std::string("new"));
        for (int n = 1; n <= 3; ++n) {
            source.recycle(entry, std::move(image));
            d.camera.azimuth = 7.0 * n;
            image = source.render(entry, d);
            QVERIFY(image == expect(d));
            QCOMPARE(frameBuffers(source, entry), std::string("recycled"));
        }
        // Not handed back: the next frame gets new buffers.
        d.camera.elevation = 10.0;
        image = source.render(entry, d);
        QVERIFY(image == expect(d));
        QCOMPARE(frameBuffers(source, entry), std::string("new"));
        // Handed back, but the next frame is of another size: new buffers again.
        source.recycle(entry, std::move(image));
        d.width = d.height = 64;
        image = source.render(entry, d);
        QVERIFY(image == expect(d));
        QCOMPARE(frameBuffers(source, entry), std::string("new"));
        // An image handed back twice, or for a series not loaded, is dropped.
        source.recycle(entry, std::move(image));
        source.recycle(entry, ImageRGBA8::filled(64, 64, 0));
        const auto other = std::make_shared<const SeriesEntry>(*entry);
        source.recycle(other, ImageRGBA8::filled(64, 64, 0));
        QVERIFY(source.lastFrameDetails(other).empty());
        image = source.render(entry, d);
        QVERIFY(image == expect(d));
        QCOMPARE(frameBuffers(source, entry), std::string("recycled"));
        source.stop();
    }
};

QTEST_GUILESS_MAIN(TestLocalFrameSource)
#include "test_local_frame_source.moc"
