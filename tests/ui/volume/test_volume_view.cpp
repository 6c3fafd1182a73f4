// The 3D view on real widgets and a real OpenGL context (llvmpipe under Xvfb):
// GPU frames against the CPU reference, mouse interaction, interactive quality,
// live transfer-function edits, the context lifecycle and the CPU fallback.
#include <QApplication>
#include <QSignalSpy>
#include <QTest>
#include <QWheelEvent>

#include <cmath>
#include <memory>
#include <vector>

#include <unistd.h>

#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "tests/support/XvfbRelaunch.h"
#include "ui/transfer/TransferFunctionCanvas.h"
#include "ui/transfer/TransferFunctionEditor.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;

namespace {

// A ball of value 1000 (radius 12 voxels) with a shell falling off to 0,
// off-centre so that rotations change the image.
std::shared_ptr<const Volume> makeBallVolume() {
    VolumeGeometry g;
    g.dims = {40, 36, 32};
    g.spacing = {1.0, 1.0, 1.2};
    auto volume = std::make_shared<Volume>(g, VoxelType::Int16);
    auto voxels = volume->voxels<std::int16_t>();
    const glm::dvec3 centre(22.0, 16.0, 15.0);
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const double r = glm::length((glm::dvec3(i, j, k) - centre) * g.spacing);
                const double v = std::clamp((16.0 - r) / 4.0, 0.0, 1.0) * 1000.0 + (i % 7) * 10;
                voxels[volume->linearIndex(i, j, k)] = static_cast<std::int16_t>(v);
            }
        }
    }
    volume->modality = "CT";
    return volume;
}

TransferFunction ballTransferFunction() {
    TransferFunction tf;
    tf.name = "ball";
    tf.opacity = {{0.0, 0.0}, {200.0, 0.0}, {1000.0, 0.5}};
    tf.colour = {{0.0, {1.0, 0.5, 0.2}}, {1000.0, {1.0, 1.0, 1.0}}};
    tf.shading.enabled = true;
    return tf;
}

ImageRGBA8 fromQImage(const QImage& source) {
    const QImage image = source.convertToFormat(QImage::Format_RGBA8888);
    ImageRGBA8 out = ImageRGBA8::filled(image.width(), image.height());
    for (int y = 0; y < image.height(); ++y) {
        std::copy_n(image.constScanLine(y), 4 * image.width(), out.at(0, y));
    }
    return out;
}

double checkedPsnr(const ImageRGBA8& actual, const ImageRGBA8& reference, const char* name) {
    const double p = psnr(actual, reference);
    if (p < 35.0) {
        const std::filesystem::path dir(LUCENT_BIN_DIR);
        writePng(actual, dir / (std::string("ui_failed_") + name + "_view.png"));
        writePng(reference, dir / (std::string("ui_failed_") + name + "_cpu.png"));
    }
    return p;
}

struct Frame {
    std::size_t samples;
    bool interactive;
};

} // namespace

class TestVolumeView : public QObject {
    Q_OBJECT

private slots:
    void init();
    void cleanup();
    void rendersLikeCpuReference();
    void framesAreDrawnInPlace();
    void dragRotatesWithInteractiveQuality();
    void wheelAndRightDragZoom();
    void transferFunctionEditsRerender();
    void survivesNewContext();
    void cpuFallbackSaysWhy();

private:
    // Waits for the next frame of the given kind; false on timeout.
    bool waitForFrame(bool interactive, int timeoutMs = 20000);

    std::shared_ptr<const Volume> volume_ = makeBallVolume();
    std::unique_ptr<VolumeView> view_;
    std::vector<Frame> frames_;
    std::vector<BackendFrame> localFrames_; // as the local backend sends them
};

void TestVolumeView::init() {
    frames_.clear();
    localFrames_.clear();
    view_ = std::make_unique<VolumeView>();
    // These compare what the screen shows with frames: no orientation cube over them.
    view_->setOrientationMarkerShown(false);
    QObject::connect(&view_->localBackend(), &RenderBackend::frameReady, view_.get(),
                     [this](const BackendFrame& f) { localFrames_.push_back(f); });
    view_->resize(160, 128);
    QObject::connect(view_.get(), &VolumeView::renderedFrame, view_.get(),
                     [this](const RenderStats& s, bool interactive) {
                         frames_.push_back({s.samples, interactive});
                     });
    view_->setVolume(volume_);
    view_->setTransferFunction(ballTransferFunction());
    view_->show();
    QVERIFY(QTest::qWaitForWindowExposed(view_.get()));
    QVERIFY2(view_->backend() == VolumeView::Backend::Gpu, qPrintable(view_->notice()));
    // The first frame may have come while the window was being exposed.
    QTRY_VERIFY_WITH_TIMEOUT(!frames_.empty(), 20000);
    QVERIFY2(view_->backend() == VolumeView::Backend::Gpu, qPrintable(view_->notice()));
}

void TestVolumeView::cleanup() {
    view_.reset();
}

bool TestVolumeView::waitForFrame(bool interactive, int timeoutMs) {
    const std::size_t before = frames_.size();
    return QTest::qWaitFor(
        [&] {
            for (std::size_t n = before; n < frames_.size(); ++n) {
                if (frames_[n].interactive == interactive) {
                    return true;
                }
            }
            return false;
        },
        timeoutMs);
}

void TestVolumeView::rendersLikeCpuReference() {
    CpuRayCaster cpu(*volume_);
    const RenderDescription d = view_->description();
    QCOMPARE(d.width, 160);
    const ImageRGBA8 reference = cpu.render(d).image;
    const double p = checkedPsnr(view_->lastFrame(), reference, "frame");
    QVERIFY2(p >= 35.0, qPrintable(QString("psnr %1 dB").arg(p)));
    // What the widget shows on screen, not only what it rendered.
    const double shown = checkedPsnr(fromQImage(view_->grabImage()), reference, "screen");
    QVERIFY2(shown >= 35.0, qPrintable(QString("psnr on screen %1 dB").arg(shown)));
    // And the image is not trivially black: the ball is there.
    const ImageRGBA8 black = ImageRGBA8::filled(d.width, d.height, 0);
    QVERIFY(psnr(reference, black) < 30.0);
}

void TestVolumeView::framesAreDrawnInPlace() {
    // The GPU frame goes straight into the widget's framebuffer: no image comes
    // with it; lastFrame() reads it back on request, and it is what the screen shows.
    Camera c = view_->camera();
    c.azimuth = 20.0;
    view_->setCamera(c);
    QVERIFY(waitForFrame(false));
    QVERIFY(!localFrames_.empty());
    QVERIFY(localFrames_.back().inPlace);
    QVERIFY(localFrames_.back().image.empty());
    QVERIFY(localFrames_.back().stats.samples > 0);
    const std::size_t framesBefore = frames_.size();
    const ImageRGBA8 screen = fromQImage(view_->grabImage());
    const ImageRGBA8 frame = view_->lastFrame();
    QCOMPARE(frame.width, 160);
    const double p = checkedPsnr(screen, frame, "in_place_screen");
    QVERIFY2(p >= 50.0, qPrintable(QString("screen against the frame read back: %1 dB").arg(p)));
    // The overlays are painted over the frame; a repaint for them casts no new frame.
    view_->setClipHandlesShown(true);
    const ImageRGBA8 withHandles = fromQImage(view_->grabImage());
    QVERIFY(withHandles != screen);
    // Lines and handles over the frame; the frame everywhere else.
    std::size_t same = 0;
    for (std::size_t n = 0; n < frame.pixels.size(); n += 4) {
        same += std::equal(frame.pixels.begin() + std::ptrdiff_t(n),
                           frame.pixels.begin() + std::ptrdiff_t(n + 4),
                           withHandles.pixels.begin() + std::ptrdiff_t(n));
    }
    QVERIFY2(same * 10 > frame.pixelCount() * 8,
             qPrintable(QString("%1 of %2 pixels as the frame").arg(same).arg(frame.pixelCount())));
    QCOMPARE(frames_.size(), framesBefore);
}

void TestVolumeView::dragRotatesWithInteractiveQuality() {
    const std::size_t fullSamples = frames_.back().samples;
    QVERIFY(fullSamples > 0);
    QSignalSpy cameraSpy(view_.get(), &VolumeView::cameraChanged);
    const QPoint start(80, 64);
    QTest::mousePress(view_.get(), Qt::LeftButton, {}, start);
    QTest::mouseMove(view_.get(), start + QPoint(40, 0));
    QVERIFY(waitForFrame(true));
    QCOMPARE(view_->camera().azimuth, 40 * VolumeView::kDegreesPerPixel);
    QTest::mouseMove(view_.get(), start + QPoint(60, -10));
    QVERIFY(waitForFrame(true));
    QCOMPARE(view_->camera().azimuth, 30.0);
    QCOMPARE(view_->camera().elevation, -5.0);
    QCOMPARE(cameraSpy.count(), 2);
    const std::size_t interactiveSamples = frames_.back().samples;
    // Half the image on each side and twice the step: about an eighth of the samples.
    QVERIFY2(interactiveSamples * 4 < fullSamples,
             qPrintable(QString("%1 vs %2").arg(interactiveSamples).arg(fullSamples)));
    QCOMPARE(view_->lastFrame().width, 160); // scaled up to the view

    QTest::mouseRelease(view_.get(), Qt::LeftButton, {}, start + QPoint(60, -10));
    QVERIFY(waitForFrame(false));
    QVERIFY(!frames_.back().interactive);
    QVERIFY(frames_.back().samples > 4 * interactiveSamples);
    // The still frame is the full-quality one for the new camera.
    CpuRayCaster cpu(*volume_);
    const double p =
        checkedPsnr(view_->lastFrame(), cpu.render(view_->description()).image, "after_drag");
    QVERIFY2(p >= 35.0, qPrintable(QString("psnr %1 dB").arg(p)));
}

void TestVolumeView::wheelAndRightDragZoom() {
    const QPointF pos(80, 64);
    QWheelEvent wheel(pos, view_->mapToGlobal(pos), QPoint(), QPoint(0, 120), Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(view_.get(), &wheel);
    QVERIFY(std::abs(view_->camera().zoom - VolumeView::kWheelZoomPerNotch) < 1e-12);
    QTest::mousePress(view_.get(), Qt::RightButton, {}, pos.toPoint());
    QTest::mouseMove(view_.get(), pos.toPoint() + QPoint(0, -50));
    QTest::mouseRelease(view_.get(), Qt::RightButton, {}, pos.toPoint() + QPoint(0, -50));
    const double expected =
        VolumeView::kWheelZoomPerNotch * std::exp(50 * VolumeView::kZoomPerPixel);
    QVERIFY(std::abs(view_->camera().zoom - expected) < 1e-12);
    QTest::mousePress(view_.get(), Qt::MiddleButton, {}, pos.toPoint());
    QTest::mouseMove(view_.get(), pos.toPoint() + QPoint(7, -3));
    QTest::mouseRelease(view_.get(), Qt::MiddleButton, {}, pos.toPoint() + QPoint(7, -3));
    // Pan moves the camera's point looked at: 7 pixels right, 3 up.
    QVERIFY(view_->camera().panRight < 0.0 && view_->camera().panUp < 0.0);
    QVERIFY(std::abs(view_->camera().panRight / view_->camera().panUp - 7.0 / 3.0) < 1e-9);
    QCOMPARE(view_->camera().azimuth, 0.0);
}

void TestVolumeView::transferFunctionEditsRerender() {
    TransferFunctionEditor editor;
    editor.resize(420, 260);
    editor.setVolume(volume_);
    editor.setTransferFunction(view_->transferFunction());
    QObject::connect(&editor, &TransferFunctionEditor::transferFunctionChanged, view_.get(),
                     &VolumeView::setTransferFunction);
    editor.show();
    QVERIFY(QTest::qWaitForWindowExposed(&editor));
    const ImageRGBA8 before = view_->lastFrame();

    // Drag the top point (1000, 0.5) to full opacity: the ball gets denser.
    TransferFunctionCanvas* canvas = editor.canvas();
    const QPoint start = canvas->opacityPointPosition(2).toPoint();
    QTest::mousePress(canvas, Qt::LeftButton, {}, start);
    QTest::mouseMove(canvas, QPoint(start.x(), static_cast<int>(canvas->yOfOpacity(1.0))));
    QVERIFY(waitForFrame(false));
    QCOMPARE(view_->transferFunction(), editor.transferFunction());
    QVERIFY(std::abs(view_->transferFunction().opacity[2].opacity - 1.0) < 0.01);
    QTest::mouseRelease(canvas, Qt::LeftButton, {}, start);
    QVERIFY2(psnr(view_->lastFrame(), before) < 40.0, "the image did not change");
    CpuRayCaster cpu(*volume_);
    const double p =
        checkedPsnr(view_->lastFrame(), cpu.render(view_->description()).image, "after_tf");
    QVERIFY2(p >= 35.0, qPrintable(QString("psnr %1 dB").arg(p)));
}

void TestVolumeView::survivesNewContext() {
    // Moving the view to another window destroys its context (the caster goes
    // with it, released first) and makes a new one.
    auto other = std::make_unique<QWidget>();
    other->resize(200, 160);
    other->show();
    QVERIFY(QTest::qWaitForWindowExposed(other.get()));
    const std::size_t before = frames_.size();
    view_->setParent(other.get());
    view_->show();
    const bool rendered = QTest::qWaitFor([&] { return frames_.size() > before; }, 20000);
    view_->setParent(nullptr); // the unique_ptr owns it
    QVERIFY2(rendered, qPrintable(view_->notice()));
    QCOMPARE(view_->backend(), VolumeView::Backend::Gpu);
    CpuRayCaster cpu(*volume_);
    const double p =
        checkedPsnr(view_->lastFrame(), cpu.render(view_->description()).image, "new_context");
    QVERIFY2(p >= 35.0, qPrintable(QString("psnr %1 dB").arg(p)));
}

void TestVolumeView::cpuFallbackSaysWhy() {
    VolumeView cpuView(nullptr, VolumeView::Backend::Cpu);
    std::vector<Frame> frames;
    QObject::connect(&cpuView, &VolumeView::renderedFrame, &cpuView,
                     [&frames](const RenderStats& s, bool i) {
                         frames.push_back({s.samples, i});
                     });
    cpuView.resize(160, 128);
    cpuView.setVolume(volume_);
    cpuView.setTransferFunction(ballTransferFunction());
    cpuView.show();
    QVERIFY(QTest::qWaitForWindowExposed(&cpuView));
    QTRY_VERIFY_WITH_TIMEOUT(!frames.empty(), 20000);
    QCOMPARE(cpuView.backend(), VolumeView::Backend::Cpu);
    QVERIFY(cpuView.notice().contains("CPU"));
    CpuRayCaster cpu(*volume_);
    QCOMPARE(cpuView.lastFrame(), cpu.render(cpuView.description()).image);
}

int main(int argc, char** argv) {
    if (const int status = lucent::test::relaunchUnderXvfbWhenHeadless(argc, argv); status >= 0) {
        return status;
    }
    QSurfaceFormat::setDefaultFormat(VolumeView::surfaceFormat());
    QApplication app(argc, argv);
    TestVolumeView test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_volume_view.moc"
