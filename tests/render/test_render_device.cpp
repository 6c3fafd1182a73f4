// The one opener: GL and the CPU through RenderDevice render the same image of
// the real CT, and a GL renderer outlives its device. (A device with no EGL
// display falls back with its reason: test_gl_cli, in a process of its own.)
#include <QTest>

#include <stdexcept>

#include "core/tf/TransferFunction.h"
#include "render/RenderDevice.h"
#include "tests/render/GlTestSupport.h"

using namespace lucent;
using namespace lucent::test;

class TestRenderDevice : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        if (!std::filesystem::exists(philipsCt())) {
            QSKIP("../shared/data is absent: no real CT to render");
        }
        volume_ = loadPath(philipsCt().string(), "", {});
    }

    // The same description through both devices, as the CLI, the server and
    // the 3D view now open them: within the GPU suite's bound of the CPU.
    void glAndCpuAgree_data() {
        QTest::addColumn<QString>("interp");
        QTest::addColumn<bool>("preintegrate");
        QTest::newRow("linear") << "linear" << false;
        QTest::newRow("cubic") << "cubic" << false;
        QTest::newRow("preintegrated") << "linear" << true;
    }
    void glAndCpuAgree() {
        QFETCH(QString, interp);
        QFETCH(bool, preintegrate);
        const std::unique_ptr<RenderDevice> gl = RenderDevice::open(RendererKind::Gl);
        QVERIFY2(gl->kind() == RendererKind::Gl, gl->fallbackReason().c_str());
        QVERIFY(gl->description().rfind("gl: ", 0) == 0);
        const std::unique_ptr<RenderDevice> cpu = RenderDevice::open(RendererKind::Cpu);
        QVERIFY(cpu->kind() == RendererKind::Cpu && cpu->fallbackReason().empty());

        RenderDescription d;
        d.volume = &volume_;
        d.width = d.height = 160;
        d.camera.azimuth = 30.0;
        d.camera.elevation = 15.0;
        d.transferFunction = loadPreset("ct-bone");
        d.sampling.interpolation = interp == "cubic" ? Interpolation::Cubic : Interpolation::Linear;
        d.sampling.preintegrate = preintegrate;

        RenderDevice::Opened g = gl->openRenderer(volume_);
        RenderDevice::Opened c = cpu->openRenderer(volume_);
        QVERIFY(g.fallbackReason.empty() && c.fallbackReason.empty());
        QCOMPARE(g.renderer->backend(), std::string("gl"));
        QCOMPARE(c.renderer->backend(), std::string("cpu"));
        const RenderResult gpuFrame = g.renderer->render(d);
        const RenderResult cpuFrame = c.renderer->render(d);
        // The GPU decides what shows from what samples in a cell read (the next
        // voxel); the CPU's bricks keep a margin of 3 for every filter.
        QVERIFY(gpuFrame.stats.bricksUsed > 0 &&
                gpuFrame.stats.bricksUsed <= cpuFrame.stats.bricksUsed);
        const double p =
            comparedPsnr(gpuFrame.image, cpuFrame.image, "device_" + interp.toStdString(), 40.0);
        QVERIFY2(p >= 40.0, qPrintable(QString("GL against CPU: %1 dB").arg(p)));
        QVERIFY(!g.renderer->frameDetails().empty()); // uploads, pool, gradients
    }

    // A renderer of a device with its own context keeps that context.
    void rendererOutlivesItsDevice() {
        std::unique_ptr<Renderer> renderer;
        {
            const std::unique_ptr<RenderDevice> gl = RenderDevice::open(RendererKind::Gl);
            renderer = gl->openRenderer(volume_).renderer;
        }
        RenderDescription d;
        d.volume = &volume_;
        d.width = d.height = 64;
        d.transferFunction = loadPreset("ct-bone");
        QCOMPARE(renderer->render(d).image.width, 64);
        QVERIFY(!renderer->device().empty());
    }

    // Two devices share the process's EGL display: ending one leaves the other working.
    void devicesShareTheDisplay() {
        auto first = std::make_unique<RenderDevice::Opened>(
            RenderDevice::open(RendererKind::Gl)->openRenderer(volume_));
        const std::unique_ptr<RenderDevice> second = RenderDevice::open(RendererKind::Gl);
        RenderDevice::Opened other = second->openRenderer(volume_);
        QVERIFY(other.fallbackReason.empty());
        RenderDescription d;
        d.volume = &volume_;
        d.width = d.height = 48;
        d.transferFunction = loadPreset("ct-bone");
        const ImageRGBA8 before = other.renderer->render(d).image;
        first.reset(); // its context, and with it (once) the display
        QVERIFY(other.renderer->render(d).image == before);
    }

    void kindsByName() {
        QVERIFY(parseRendererKind("gl") == RendererKind::Gl);
        QVERIFY(parseRendererKind("cpu") == RendererKind::Cpu);
        try {
            parseRendererKind("vulkan");
            QFAIL("vulkan was accepted");
        } catch (const std::invalid_argument& e) {
            QVERIFY(std::string(e.what()).find("cpu, gl") != std::string::npos);
        }
    }

private:
    Volume volume_;
};

QTEST_GUILESS_MAIN(TestRenderDevice)
#include "test_render_device.moc"
