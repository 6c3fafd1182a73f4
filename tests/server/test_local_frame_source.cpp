// The render server's frames drawn in this process on the CPU (no GL): once
// the render thread hands an encoded image back, the next frame of its size is
// drawn into its buffers and equals a fresh caster's; an image not handed
// back, or one of another size, leaves the next frame with new buffers; what
// is not a whole frame is dropped. The
// render thread's worker hands back every frame it encoded.
#include <QImage>
#include <QTest>

#include <memory>
#include <string>

#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/tf/TransferFunction.h"
#include "protocol/FrameMessage.h"
#include "server/LocalFrameSource.h"
#include "server/RenderWorker.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/support/RealData.h"

using namespace lucent;
using namespace lucent::test;

namespace {

const char* const kCt = "dcm_qa_ct/Philips_S21570/S2010";

ImageRGBA8 decodedPng(const QByteArray& message) {
    const remote::ParsedFrame parsed = remote::parseFrameMessage(
        std::string_view(message.constData(), std::size_t(message.size())));
    const QImage q =
        QImage::fromData(QByteArray(parsed.image.data(), qsizetype(parsed.image.size())), "PNG")
            .convertToFormat(QImage::Format_RGBA8888);
    ImageRGBA8 out = ImageRGBA8::filled(q.width(), q.height());
    for (int y = 0; y < q.height(); ++y) {
        std::copy_n(q.constScanLine(y), 4 * q.width(), out.at(0, y));
    }
    return out;
}

// A frame with an image and nothing else: not one a caster made.
RenderResult imageOnly(int side) {
    RenderResult r;
    r.image = ImageRGBA8::filled(side, side, 0);
    return r;
}

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
        RenderResult frame = source.render(entry, d);
        QVERIFY(frame.image == expect(d));
        QCOMPARE(frameBuffers(source, entry), std::string("new"));
        for (int n = 1; n <= 3; ++n) {
            source.recycle(entry, std::move(frame));
            d.camera.azimuth = 7.0 * n;
            frame = source.render(entry, d);
            QVERIFY(frame.image == expect(d));
            QCOMPARE(frameBuffers(source, entry), std::string("recycled"));
        }
        // Not handed back: the next frame gets new buffers.
        d.camera.elevation = 10.0;
        frame = source.render(entry, d);
        QVERIFY(frame.image == expect(d));
        QCOMPARE(frameBuffers(source, entry), std::string("new"));
        // Handed back, but the next frame is of another size: new buffers again.
        source.recycle(entry, std::move(frame));
        d.width = d.height = 64;
        frame = source.render(entry, d);
        QVERIFY(frame.image == expect(d));
        QCOMPARE(frameBuffers(source, entry), std::string("new"));
        // A second hand-back of what is not a whole frame, or one for a series not
        // loaded, is dropped.
        source.recycle(entry, std::move(frame));
        source.recycle(entry, imageOnly(64));
        const auto other = std::make_shared<const SeriesEntry>(*entry);
        source.recycle(other, imageOnly(64));
        QVERIFY(source.lastFrameDetails(other).empty());
        frame = source.render(entry, d);
        QVERIFY(frame.image == expect(d));
        QCOMPARE(frameBuffers(source, entry), std::string("recycled"));
        source.stop();
    }

    void theRenderThreadHandsEncodedFramesBack() {
        REQUIRE_DATA(kCt);
        const auto entry =
            std::make_shared<const SeriesEntry>(scanPath(kRealData / kCt).series.front());
        const Volume volume = loadSeries(*entry);
        auto owned = std::make_unique<remote::LocalFrameSource>(RendererKind::Cpu);
        const remote::LocalFrameSource& source = *owned;
        remote::RenderWorker worker(std::move(owned));
        QVERIFY(worker.start().startsWith("cpu"));
        std::vector<remote::RenderedFrame> frames;
        QObject::connect(&worker, &remote::RenderWorker::frameRendered,
                         [&](const remote::RenderedFrame& f) { frames.push_back(f); });
        remote::RenderJob job;
        job.view = 1;
        job.series = entry;
        job.description = describe(volume, loadPreset("ct-bone"), 96);
        job.description.volume = nullptr;
        for (int n = 0; n < 3; ++n) {
            job.seq = std::uint64_t(n + 1);
            job.description.camera.azimuth = 7.0 * n;
            worker.render(job);
            QCOMPARE(int(frames.size()), n + 1);
            QVERIFY2(frames.back().error.isEmpty(), qPrintable(frames.back().error));
            RenderDescription own = job.description;
            own.volume = &volume;
            QVERIFY(decodedPng(frames.back().message) == CpuRayCaster(volume).render(own).image);
            QCOMPARE(frameBuffers(source, entry), std::string(n == 0 ? "new" : "recycled"));
        }
        worker.stop();
    }
};

QTEST_GUILESS_MAIN(TestLocalFrameSource)
#include "test_local_frame_source.moc"
