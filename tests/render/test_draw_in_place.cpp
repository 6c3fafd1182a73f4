// GpuRayCaster::drawInPlace, the 3D view's path: the frame drawn straight into
// a framebuffer, read back here from that framebuffer, against the frame
// render() reads back (the same rays: exact, or 50 dB) and the CPU reference
// (40 dB, as the other GL tests); a smaller interactive frame stretched to the
// rectangle against scaledTo(); a rectangle inside a larger framebuffer; the
// frame kept for a repaint; the renderers RenderDevice opens.
#include <QTest>

#include <chrono>
#include <stdexcept>

#include "core/quality/InteractiveQuality.h"
#include "render/GlObjects_p.h"
#include "render/RenderDevice.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/render/GlTestSupport.h"

using namespace lucent;
using namespace lucent::test;

namespace {

// The test's volume with an oblique direction and uneven spacing (as
// test_gpu_ray_caster's), int16.
Volume madeVolume() {
    Volume v = makeVolume(
        {70, 61, 45},
        [](int i, int j, int k) {
            const glm::dvec3 p(i, j, k);
            const double r = glm::length(p - glm::dvec3(35, 30, 22));
            const double shell = std::abs(r - 17.0) < 2.5 && p.z < 34 ? 420.0 : 0.0;
            return -200.0 + 6.0 * blobs(i / 2, j / 2, k) + shell;
        },
        VoxelType::Int16);
    VolumeGeometry g = v.geometry();
    g.spacing = {0.8, 0.8, 1.5};
    const double a = 0.3;
    g.direction =
        glm::dmat3({std::cos(a), std::sin(a), 0}, {-std::sin(a), std::cos(a), 0}, {0, 0, 1});
    v.setGeometry(g);
    return v;
}

TransferFunction madeTf() {
    TransferFunction tf;
    tf.name = "made";
    tf.opacity = {{0.0, 0.0}, {150.0, 0.05}, {300.0, 0.5}, {600.0, 0.9}};
    tf.colour = {{0.0, {0.9, 0.4, 0.3}}, {300.0, {1.0, 0.9, 0.7}}, {600.0, {1, 1, 1}}};
    tf.shading.enabled = true;
    return tf;
}

RenderDescription doublePrecision(RenderDescription d) {
    d.sampling.precision = Precision::Double;
    return d;
}

int maxDifference(const ImageRGBA8& a, const ImageRGBA8& b) {
    int most = 0;
    for (std::size_t n = 0; n < a.pixels.size() && n < b.pixels.size(); ++n) {
        most = std::max(most, std::abs(int(a.pixels[n]) - int(b.pixels[n])));
    }
    return most;
}

} // namespace

class TestDrawInPlace : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;
    Volume made_ = madeVolume();

    // The frame drawn in place and the one read back, and the CPU reference.
    void compareWithReadBack(const Volume& volume, const RenderDescription& d,
                             const std::string& name) {
        GpuRayCaster gpu(volume);
        TestFramebuffer fb(d.width, d.height);
        fb.clear({1.0f, 0.0f, 1.0f, 1.0f}); // every pixel must be drawn over
        const RenderStats drawn = gpu.drawInPlace(d, fb.whole());
        const ImageRGBA8 inPlace = fb.read();
        const RenderResult readBack = gpu.render(d); // cast again, and read back
        const double p = comparedPsnr(inPlace, readBack.image, name + "_vs_read_back", 50.0);
        qInfo("%s: %.2f dB against the read back (largest difference %d), samples %zu",
              name.c_str(), p, maxDifference(inPlace, readBack.image), drawn.samples);
        QVERIFY2(p >= 50.0, qPrintable(QString("%1 dB against the read back").arg(p)));
        // Counted per row in place, per pixel from the read back: the same rays.
        QCOMPARE(drawn.samples, readBack.stats.samples);
        QVERIFY(drawn.samples > 0);
        QCOMPARE(drawn.bricksUsed, readBack.stats.bricksUsed);
        QCOMPARE(drawn.bricksTotal, readBack.stats.bricksTotal);
        QCOMPARE(drawn.lod, readBack.stats.lod);
        const ImageRGBA8 cpu = CpuRayCaster(volume).render(doublePrecision(d)).image;
        const double q = comparedPsnr(inPlace, cpu, name + "_vs_cpu", 40.0);
        QVERIFY2(q >= 40.0, qPrintable(QString("%1 dB against the CPU reference").arg(q)));
        // Not trivially one colour: the volume is in the picture.
        QVERIFY(psnr(cpu, ImageRGBA8::filled(d.width, d.height, 0)) < 30.0 ||
                d.background != glm::dvec3(0.0));
    }

private slots:
    void initTestCase() {
        context_ = OffscreenContext::create();
        qInfo("GL: %s", context_->description().c_str());
    }

    void matchesReadBack_data() {
        QTest::addColumn<int>("mode");
        QTest::addColumn<int>("interpolation");
        QTest::addColumn<double>("red"); // the background
        QTest::addColumn<double>("green");
        QTest::addColumn<double>("blue");
        QTest::newRow("dvr-linear")
            << int(RenderMode::Dvr) << int(Interpolation::Linear) << 0.0 << 0.0 << 0.0;
        QTest::newRow("dvr-cubic-over-grey-blue")
            << int(RenderMode::Dvr) << int(Interpolation::Cubic) << 0.2 << 0.3 << 0.45;
        QTest::newRow("mip-linear")
            << int(RenderMode::Mip) << int(Interpolation::Linear) << 0.0 << 0.0 << 0.0;
        QTest::newRow("iso-linear")
            << int(RenderMode::Isosurface) << int(Interpolation::Linear) << 0.1 << 0.1 << 0.1;
    }
    void matchesReadBack() {
        QFETCH(int, mode);
        QFETCH(int, interpolation);
        QFETCH(double, red);
        QFETCH(double, green);
        QFETCH(double, blue);
        RenderDescription d = describe(made_, madeTf());
        d.width = 120; // not square, not a power of two
        d.height = 94;
        d.camera.azimuth = 30.0;
        d.camera.elevation = 20.0;
        d.mode = RenderMode(mode);
        d.isoValue = 200.0;
        d.sampling.interpolation = Interpolation(interpolation);
        d.background = glm::dvec3(red, green, blue);
        compareWithReadBack(made_, d, std::string("made_") + QTest::currentDataTag());
    }

    void matchesReadBackOnPhilipsCt() {
        if (!std::filesystem::exists(philipsCt())) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2020");
        }
        const Volume ct = loadPath(philipsCt());
        RenderDescription d = describe(ct, loadPreset("ct-bone"));
        d.width = 160;
        d.height = 128;
        compareWithReadBack(ct, d, "philips_ct_bone");
    }

    // While dragging: half the image on each side, stretched to the rectangle
    // by the sampler, as scaledTo() stretched the read back image before.
    void stretchesInteractiveFrame_data() {
        QTest::addColumn<int>("width");
        QTest::addColumn<int>("height");
        QTest::addColumn<int>("divisor");
        QTest::newRow("160x128-half") << 160 << 128 << 2;
        QTest::newRow("151x97-third") << 151 << 97 << 3; // ratios that are not whole
    }
    void stretchesInteractiveFrame() {
        QFETCH(int, width);
        QFETCH(int, height);
        QFETCH(int, divisor);
        RenderDescription still = describe(made_, madeTf());
        still.width = width;
        still.height = height;
        still.camera.azimuth = -40.0;
        InteractiveQuality quality;
        quality.imageScale = 1.0 / divisor;
        const RenderDescription d = interactiveDescription(still, quality);
        QVERIFY(d.width < width);
        GpuRayCaster gpu(made_);
        TestFramebuffer fb(width, height);
        fb.clear({1.0f, 0.0f, 1.0f, 1.0f});
        const RenderStats drawn = gpu.drawInPlace(d, fb.whole());
        const ImageRGBA8 inPlace = fb.read();
        const RenderResult small = gpu.render(d);
        QCOMPARE(drawn.samples, small.stats.samples);
        const ImageRGBA8 scaled = scaledTo(small.image, width, height);
        const std::string name = std::string("stretched_") + QTest::currentDataTag();
        // Both composite into 8 bits and then interpolate; the sampler's
        // weights are not scaledTo()'s doubles: a difference of one at most.
        const double p = comparedPsnr(inPlace, scaled, name + "_vs_scaled", 50.0);
        qInfo("%s: %.2f dB against the scaled read back (largest difference %d)", name.c_str(), p,
              maxDifference(inPlace, scaled));
        QVERIFY2(p >= 50.0, qPrintable(QString("%1 dB against scaledTo()").arg(p)));
        QVERIFY(maxDifference(inPlace, scaled) <= 1);
        const ImageRGBA8 cpu =
            scaledTo(CpuRayCaster(made_).render(doublePrecision(d)).image, width, height);
        const double q = comparedPsnr(inPlace, cpu, name + "_vs_cpu", 40.0);
        QVERIFY2(q >= 40.0, qPrintable(QString("%1 dB against the CPU reference").arg(q)));
    }

    // A rectangle inside a larger framebuffer: drawn there, nothing else touched.
    void drawsIntoItsRectangleOnly() {
        RenderDescription d = describe(made_, madeTf());
        d.width = 100;
        d.height = 80;
        GpuRayCaster gpu(made_);
        TestFramebuffer fb(170, 130);
        fb.clear({0.2f, 0.4f, 0.6f, 1.0f});
        const FramebufferTarget target{fb.name(), 40, 30, 100, 80};
        gpu.drawInPlace(d, target);
        const ImageRGBA8 all = fb.read();
        const ImageRGBA8 inside = fb.read(40, 30, 100, 80);
        const double p = comparedPsnr(inside, gpu.render(d).image, "rectangle", 50.0);
        QVERIFY2(p >= 50.0, qPrintable(QString("%1 dB inside the rectangle").arg(p)));
        // GL row 30 from the bottom is image row 130 - 1 - 30 from the top.
        int outside = 0, touched = 0;
        for (int y = 0; y < all.height; ++y) {
            for (int x = 0; x < all.width; ++x) {
                const int glY = all.height - 1 - y;
                if (x >= 40 && x < 140 && glY >= 30 && glY < 110) {
                    continue;
                }
                ++outside;
                const std::uint8_t* px = all.at(x, y);
                touched += px[0] != 51 || px[1] != 102 || px[2] != 153 || px[3] != 255;
            }
        }
        QCOMPARE(outside, 170 * 130 - 100 * 80);
        QCOMPARE(touched, 0);

        // clearFramebuffer: its rectangle only, opaque.
        clearFramebuffer({fb.name(), 0, 0, 10, 20}, glm::dvec3(1.0, 0.5, 0.0));
        const ImageRGBA8 cleared = fb.read(0, 0, 11, 21);
        QCOMPARE(int(cleared.at(0, 20)[0]), 255); // GL (0, 0)
        QCOMPARE(int(cleared.at(9, 1)[1]), 128);  // GL (9, 19)
        QCOMPARE(int(cleared.at(9, 1)[3]), 255);
        QCOMPARE(int(cleared.at(10, 1)[0]), 51); // GL (10, 19): outside
        QCOMPARE(int(cleared.at(0, 0)[0]), 51);  // GL (0, 20): outside
    }

    // A repaint of the same description draws the frame kept; a description
    // that casts differently is cast again; another background only
    // composites the kept frame over it.
    void repaintsTheKeptFrame() {
        RenderDescription d = describe(made_, madeTf());
        d.width = 128;
        d.height = 96;
        GpuRayCaster gpu(made_);
        TestFramebuffer fb(128, 96);
        using Clock = std::chrono::steady_clock;
        auto t0 = Clock::now();
        const RenderStats first = gpu.drawInPlace(d, fb.whole());
        const ImageRGBA8 image = fb.read();
        const double castMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();

        fb.clear({0.0f, 0.0f, 0.0f, 1.0f});
        t0 = Clock::now();
        const RenderStats again = gpu.drawInPlace(d, fb.whole());
        QCOMPARE(fb.read(), image);
        const double repaintMs =
            std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        QCOMPARE(again.samples, first.samples);
        QCOMPARE(again.bricksUsed, first.bricksUsed);
        qInfo("cast and draw %.2f ms, repaint of the kept frame %.2f ms", castMs, repaintMs);

        RenderDescription other = d;
        other.camera.azimuth = 25.0;
        gpu.drawInPlace(other, fb.whole());
        const ImageRGBA8 turned = fb.read();
        QVERIFY(psnr(turned, image) < 40.0);
        QVERIFY(comparedPsnr(turned, gpu.render(other).image, "turned", 50.0) >= 50.0);

        other.background = glm::dvec3(0.5, 0.25, 0.0);
        gpu.drawInPlace(other, fb.whole());
        QVERIFY(comparedPsnr(fb.read(), gpu.render(other).image, "background", 50.0) >= 50.0);

        // After render() of a description the target holds that one's frame.
        other.sampling.step = 0.25;
        const ImageRGBA8 fine = gpu.render(other).image;
        fb.clear({0.0f, 0.0f, 0.0f, 1.0f});
        gpu.drawInPlace(other, fb.whole());
        QVERIFY(comparedPsnr(fb.read(), fine, "after_render", 50.0) >= 50.0);
        gpu.drawInPlace(d, fb.whole());
        QCOMPARE(fb.read(), image);
    }

    // The renderers RenderDevice opens: GL draws in place (in its own context,
    // current when it draws), the CPU refuses to.
    void rendererFromDeviceDrawsInPlace() {
        // One EGL context at a time: the last one to go terminates the display
        // the others share (OffscreenContext), so this test's goes first.
        context_.reset();
        {
            const std::unique_ptr<RenderDevice> device = RenderDevice::open(RendererKind::Gl);
            QVERIFY2(device->kind() == RendererKind::Gl, device->fallbackReason().c_str());
            RenderDevice::Opened opened = device->openRenderer(made_);
            QVERIFY2(opened.fallbackReason.empty(), opened.fallbackReason.c_str());
            QVERIFY(opened.renderer->drawsInPlace());
            RenderDescription d = describe(made_, madeTf());
            d.width = 64;
            d.height = 48;
            TestFramebuffer fb(64, 48); // in the device's context, current since open()
            const RenderStats stats = opened.renderer->drawInPlace(d, fb.whole());
            QVERIFY(stats.samples > 0);
            const ImageRGBA8 inPlace = fb.read();
            QVERIFY(comparedPsnr(inPlace, opened.renderer->render(d).image, "device", 50.0) >=
                    50.0);
        }
        context_ = OffscreenContext::create();
        const std::unique_ptr<Renderer> cpu =
            RenderDevice::open(RendererKind::Cpu)->openRenderer(made_).renderer;
        QVERIFY(!cpu->drawsInPlace());
        QVERIFY_THROWS_EXCEPTION(std::logic_error,
                                 cpu->drawInPlace(describe(made_, madeTf()), {0, 0, 0, 8, 8}));
        GpuRayCaster gpu(made_);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 gpu.drawInPlace(describe(made_, madeTf()), {0, 0, 0, 0, 8}));
    }
};

QTEST_GUILESS_MAIN(TestDrawInPlace)
#include "test_draw_in_place.moc"
