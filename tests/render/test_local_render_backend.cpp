// The workstation's local backend on the CPU (no GL): a drag's frames on the
// real CT each equal a fresh caster's, and from the second frame of a size on
// they are drawn into the buffers of the frame shown before (handed back once
// the receivers have copied it); a still frame of another size gets new ones.
#include <QTest>

#include <memory>
#include <string>
#include <vector>

#include "core/io/Catalog.h"
#include "core/quality/InteractiveQuality.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/tf/TransferFunction.h"
#include "render/LocalRenderBackend.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/support/RealData.h"

using namespace lucent;
using namespace lucent::test;

namespace {

const char* const kCt = "dcm_qa_ct/Philips_S21570/S2010";

} // namespace

class TestLocalRenderBackend : public QObject {
    Q_OBJECT

private slots:
    void cpuDragDrawsIntoTheFrameShownBefore() {
        REQUIRE_DATA(kCt);
        const auto volume = std::make_shared<const Volume>(loadPath(kRealData / kCt));
        RenderDescription still = describe(*volume, loadPreset("ct-bone"), 128);
        LocalRenderBackend backend;
        backend.setKind(RendererKind::Cpu);
        backend.setVolume(volume);
        std::vector<ImageRGBA8> shown; // what a receiver keeps: a copy
        QObject::connect(&backend, &RenderBackend::frameReady,
                         [&](const BackendFrame& frame) { shown.push_back(frame.image); });
        QVERIFY(backend.lastFrameDetails().empty());
        FrameOptions drag;
        drag.interactive = true;
        for (int n = 0; n < 4; ++n) {
            still.camera.azimuth = 5.0 * n;
            backend.request(still, drag);
            backend.renderPending();
            QCOMPARE(int(shown.size()), n + 1);
            const RenderDescription d = interactiveDescription(still, drag.quality);
            QVERIFY(shown.back() == CpuRayCaster(*volume).render(d).image);
            QCOMPARE(frameDetail(backend.lastFrameDetails(), "frame_buffers").value_or("(none)"),
                     std::string(n == 0 ? "new" : "recycled"));
        }
        // Let go: the still frame is twice the size, so its buffers are new.
        backend.request(still, {});
        backend.renderPending();
        QVERIFY(shown.back() == CpuRayCaster(*volume).render(still).image);
        QCOMPARE(frameDetail(backend.lastFrameDetails(), "frame_buffers").value_or("(none)"),
                 std::string("new"));
        // A new drag: its first frame gets new buffers (the spare ones are the still frame's
        // size), the next ones the frame shown before it.
        backend.request(still, drag);
        backend.renderPending();
        QCOMPARE(frameDetail(backend.lastFrameDetails(), "frame_buffers").value_or("(none)"),
                 std::string("new"));
        backend.request(still, drag);
        backend.renderPending();
        QCOMPARE(frameDetail(backend.lastFrameDetails(), "frame_buffers").value_or("(none)"),
                 std::string("recycled"));
    }
};

QTEST_GUILESS_MAIN(TestLocalRenderBackend)
#include "test_local_render_backend.moc"
