// Benchmark (label perf): the time of one interactive frame of the 3D view,
// at 512 x 512 and 1024 x 1024, the two ways a frame has reached the screen:
//  (a) readback: the old VolumeGlSurface path. The interactive description
//      rendered and read back (Renderer::render: float RGBA and the sample
//      counts, composited over the background in a double loop), scaled up
//      to the view (scaledTo, as VolumeView::onFrame did) and painted with
//      QPainter::drawImage into the QOpenGLWidget's framebuffer (uploaded
//      again into the same context).
//  (b) inplace: Renderer::drawInPlace into the widget's framebuffer (the
//      frame stretched in the shader), then a QPainter for the overlays.
// Both in paintGL of one QOpenGLWidget (4.3 core: llvmpipe under Xvfb here,
// started by the test itself without a display), with the same GPU ray caster
// opened through RenderDevice::borrowCurrentContext(), on the Philips CT with
// ct-bone and the default interactive quality (half the image on each side,
// twice the step); and again with the volume a few pixels wide (zoom 0.03),
// where the cast costs next to nothing and the difference stands out from
// the noise of a busy machine. The two alternate frame by frame, each frame one degree
// further round, so that every frame is cast. frame_ms: from paintGL's start
// to a glFinish at its end (the GPU's work included); repaint_ms: from the
// widget's update() to its paint done (the event loop's delivery and Qt's
// composition of the window included). Medians
// of LUCENT_BENCH_FRAMES (default 10) frames each, after a warm-up, the
// fastest of each, and the median of the paired differences. Prints
// the figures, and asserts only that both paths show the same picture.
#include <QApplication>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QOpenGLWidget>
#include <QPainter>
#include <QTest>

#include <chrono>
#include <cstdlib>
#include <filesystem>

#include "app/bench/BenchScenes.h"
#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/quality/InteractiveQuality.h"
#include "render/RenderDevice.h"
#include "tests/support/XvfbRelaunch.h"

using namespace lucent;
using Clock = std::chrono::steady_clock;

namespace {

std::filesystem::path philips() {
    return std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2020";
}

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

int benchFrames() {
    const char* e = std::getenv("LUCENT_BENCH_FRAMES");
    return e != nullptr ? std::max(1, std::atoi(e)) : 10;
}

enum class Path { ReadBack, InPlace };

ImageRGBA8 fromQImage(const QImage& source) {
    const QImage image = source.convertToFormat(QImage::Format_RGBA8888);
    ImageRGBA8 out = ImageRGBA8::filled(image.width(), image.height());
    for (int y = 0; y < image.height(); ++y) {
        std::copy_n(image.constScanLine(y), 4 * image.width(), out.at(0, y));
    }
    return out;
}

// The 3D view's GL surface reduced to its frame: paintGL draws `still`'s
// interactive frame one way or the other and times it.
class FrameSurface : public QOpenGLWidget {
public:
    FrameSurface(const Volume& volume, RenderDescription still)
        : volume_(volume), still_(std::move(still)) {
        setFixedSize(still_.width, still_.height);
    }
    ~FrameSurface() override {
        makeCurrent();
        renderer_.reset();
        doneCurrent();
    }
    void setPath(Path path) { path_ = path; }
    void setAzimuth(double degrees) { still_.camera.azimuth = degrees; }
    double frameMs() const { return frameMs_; }
    int paints() const { return paints_; }
    const std::string& device() const { return device_; }

protected:
    void paintGL() override {
        QOpenGLFunctions* gl = context()->functions();
        if (!renderer_) {
            RenderDevice::Opened opened =
                RenderDevice::borrowCurrentContext()->openRenderer(volume_);
            if (!opened.fallbackReason.empty()) {
                qFatal("no GPU ray caster in the widget's context: %s",
                       opened.fallbackReason.c_str());
            }
            renderer_ = std::move(opened.renderer);
            device_ = renderer_->device();
        }
        const RenderDescription d = interactiveDescription(still_);
        const QSize pixels = size() * devicePixelRatio();
        const auto t0 = Clock::now();
        if (path_ == Path::ReadBack) {
            // As VolumeGlSurface::paintGL, VolumeView::onFrame and paintFrame did.
            gl->glClearColor(0.f, 0.f, 0.f, 1.f);
            gl->glClear(GL_COLOR_BUFFER_BIT);
            const ImageRGBA8 frame =
                scaledTo(renderer_->render(d).image, still_.width, still_.height);
            gl->glBindFramebuffer(GL_FRAMEBUFFER, defaultFramebufferObject());
            gl->glViewport(0, 0, pixels.width(), pixels.height());
            QPainter painter(this);
            const QRectF area(0, 0, width(), height());
            painter.fillRect(area, Qt::black);
            const QImage image(frame.pixels.data(), frame.width, frame.height, 4 * frame.width,
                               QImage::Format_RGBA8888);
            painter.setRenderHint(QPainter::SmoothPixmapTransform, false);
            painter.drawImage(area, image);
        } else {
            renderer_->drawInPlace(
                d, {defaultFramebufferObject(), 0, 0, pixels.width(), pixels.height()});
            QPainter painter(this); // the view's overlays go over it
        }
        gl->glFinish();
        frameMs_ = msSince(t0);
        ++paints_;
    }

private:
    const Volume& volume_;
    RenderDescription still_;
    Path path_ = Path::InPlace;
    std::unique_ptr<Renderer> renderer_;
    std::string device_;
    double frameMs_ = 0.0;
    int paints_ = 0;
};

} // namespace

class BenchViewFrame : public QObject {
    Q_OBJECT

private slots:
    void interactiveFrame_data() {
        QTest::addColumn<int>("size");
        QTest::addColumn<double>("zoom");
        QTest::newRow("512x512") << 512 << 1.0;
        QTest::newRow("1024x1024") << 1024 << 1.0;
        // The volume a few pixels wide: the cast costs next to nothing, what
        // is left is what bringing a frame to the screen costs either way.
        QTest::newRow("512x512-display-only") << 512 << 0.03;
        QTest::newRow("1024x1024-display-only") << 1024 << 0.03;
    }
    void interactiveFrame() {
        QFETCH(int, size);
        QFETCH(double, zoom);
        if (!std::filesystem::exists(philips())) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2020");
        }
        const Volume volume = loadPath(philips());
        RenderDescription still;
        still.volume = &volume;
        still.transferFunction = loadPreset("ct-bone");
        still.width = still.height = size;
        still.camera.zoom = zoom;
        FrameSurface surface(volume, still);
        surface.show();
        QVERIFY(QTest::qWaitForWindowExposed(&surface));

        double azimuth = 0.0;
        // As the view asks for a frame: update(), and the paint comes from the event loop.
        const auto frame = [&](Path path) {
            surface.setPath(path);
            surface.setAzimuth(azimuth);
            azimuth += 1.0;
            const int before = surface.paints();
            const auto t0 = Clock::now();
            surface.update();
            if (!QTest::qWaitFor([&] { return surface.paints() > before; }, 120000)) {
                qFatal("the widget did not repaint");
            }
            return std::pair{surface.frameMs(), msSince(t0)};
        };
        // Warm-up: the shaders compile, the bricks upload.
        frame(Path::ReadBack);
        frame(Path::InPlace);
        std::vector<double> readBackMs, inPlaceMs, readBackRepaint, inPlaceRepaint;
        for (int n = 0; n < benchFrames(); ++n) {
            const auto [a, ar] = frame(Path::ReadBack);
            readBackMs.push_back(a);
            readBackRepaint.push_back(ar);
            const auto [b, br] = frame(Path::InPlace);
            inPlaceMs.push_back(b);
            inPlaceRepaint.push_back(br);
        }
        // The same camera both ways: the same picture on the screen.
        surface.setAzimuth(azimuth);
        surface.setPath(Path::ReadBack);
        const ImageRGBA8 shownReadBack = fromQImage(surface.grabFramebuffer());
        surface.setAzimuth(azimuth);
        surface.setPath(Path::InPlace);
        const ImageRGBA8 shownInPlace = fromQImage(surface.grabFramebuffer());
        const double p = psnr(shownInPlace, shownReadBack);

        // Frames alternate, so a pair saw about the same load (others' work on
        // this machine): the saving is the median of the pairs' differences.
        std::vector<double> saved;
        for (std::size_t n = 0; n < readBackMs.size(); ++n) {
            saved.push_back(readBackMs[n] - inPlaceMs[n]);
        }
        const RenderDescription d = interactiveDescription(still);
        const double a = bench::median(readBackMs), b = bench::median(inPlaceMs);
        qInfo("view_frame size=%d zoom=%.2f (interactive %dx%d, step %.2f) readback_ms=%.1f "
              "inplace_ms=%.1f saved_ms=%.1f (%.0f%%; medians of %d) readback_min_ms=%.1f "
              "inplace_min_ms=%.1f readback_repaint_ms=%.1f inplace_repaint_ms=%.1f "
              "psnr_db=%.2f on %s",
              size, zoom, d.width, d.height, d.sampling.step, a, b, bench::median(saved),
              100.0 * bench::median(saved) / a, int(readBackMs.size()),
              *std::min_element(readBackMs.begin(), readBackMs.end()),
              *std::min_element(inPlaceMs.begin(), inPlaceMs.end()), bench::median(readBackRepaint),
              bench::median(inPlaceRepaint), p, surface.device().c_str());
        QVERIFY2(p >= 50.0, qPrintable(QString("the two paths differ: %1 dB").arg(p)));
    }
};

int main(int argc, char** argv) {
    if (const int status = lucent::test::relaunchUnderXvfbWhenHeadless(argc, argv); status >= 0) {
        return status;
    }
    QSurfaceFormat format = QSurfaceFormat::defaultFormat();
    format.setVersion(4, 3);
    format.setProfile(QSurfaceFormat::CoreProfile);
    QSurfaceFormat::setDefaultFormat(format);
    QApplication app(argc, argv);
    BenchViewFrame bench;
    return QTest::qExec(&bench, argc, argv);
}

#include "bench_view_frame.moc"
