// A surface drawn with the volume (GpuRayCaster::setSurface): rays stop at it
// and composite over it, against the CPU reference clipped at the surface; a
// box hides the volume behind it and nothing else; the surface alone; viridis'
// ends on a field; drawn in place as read back; displays replaced and removed;
// LocalRenderBackend keeping it for the GL renderer.
#include <QTest>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/image/ColourMap.h"
#include "core/quality/InteractiveQuality.h"
#include "core/scene/SurfaceDisplay.h"
#include "core/scene/ViewFrame.h"
#include "render/GlObjects_p.h"
#include "render/LocalRenderBackend.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/render/GlTestSupport.h"
#include "tests/render/SurfaceScenes.h"

using namespace lucent;
using namespace lucent::test;

class TestSurfaceInVolume : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenContext> context_;
    std::shared_ptr<const Volume> volume_ = std::make_shared<const Volume>(sceneVolume());
    const glm::dvec3 boxLo_{12, 24, 12}, boxHi_{27, 32, 27}; // in front of the slab
    const glm::dvec3 red_{0.8, 0.25, 0.2};

    RenderDescription slabScene(int width = 112, int height = 96) const {
        RenderDescription d = describe(*volume_, slabTf(), width);
        d.height = height;
        d.background = {0.2, 0.3, 0.4};
        return d;
    }
    std::chrono::steady_clock::time_point start_;

private slots:
    void initTestCase() {
        context_ = OffscreenContext::create();
        qInfo("GL: %s", context_->description().c_str());
    }
    void init() { start_ = std::chrono::steady_clock::now(); }
    void cleanup() {
        qInfo("%.2f s",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
    }

    // (a) Rays stop at an opaque plane across the view: the GPU frame is the
    // CPU reference clipped at the plane (its lattice is the same: the box
    // anchors it), composited over the plane's lit colour. 40 dB, as every
    // GPU-against-CPU bound here (float march, 8-bit filter weights); a
    // sample more or less on each ray costs far more (checked).
    void raysStopAtThePlane_data() {
        QTest::addColumn<int>("mode");
        QTest::newRow("dvr") << int(RenderMode::Dvr);
        QTest::newRow("mip") << int(RenderMode::Mip);
    }
    void raysStopAtThePlane() {
        QFETCH(int, mode);
        RenderDescription d = describe(*volume_, layerTf(), 96);
        d.mode = RenderMode(mode);
        d.background = {0.1, 0.1, 0.15};
        const glm::dvec3 colour(0.2, 0.9, 0.9); // unlike the layer's
        GpuRayCaster gpu(*volume_);
        QVERIFY(gpu.setSurface(plain(quadAt(kPlaneY, -200.0, 240.0), colour)));
        const RenderResult frame = gpu.render(d);

        CpuRayCaster cpu(*volume_);
        RenderDescription clipped = d;
        clipped.sampling.precision = Precision::Double;
        clipped.clip.hi.y = kPlaneY;
        const ImageRGBA8 expected = overPlane(cpu.render(clipped), d, colour);
        const std::string name = std::string("plane_") + QTest::currentDataTag();
        const double p = comparedPsnr(frame.image, expected, name, 40.0);
        clipped.clip.hi.y = kPlaneY + d.sampling.step; // a sample further on every ray
        const double further = psnr(expected, overPlane(cpu.render(clipped), d, colour));
        clipped.clip.hi.y = 1e300; // not stopped
        const double through = psnr(expected, overPlane(cpu.render(clipped), d, colour));
        qInfo("%s: %.2f dB against the CPU clipped at the plane; a sample further %.2f dB, "
              "through %.2f dB",
              name.c_str(), p, further, through);
        QVERIFY2(p >= 40.0, qPrintable(QString("%1 dB").arg(p)));
        // What the bound tells apart: rays that go on; in DVR one sample more.
        QVERIFY(through < 30.0);
        if (d.mode == RenderMode::Dvr) {
            QVERIFY(further < 37.0);
        }
    }

    // (b) A closed box in front of the slab: where it shows, its lit front
    // face, and the slab (which shows there without it) does not; elsewhere the
    // frame without the surface. An eye inside the box sees its back faces only.
    void boxHidesTheVolumeBehind() {
        RenderDescription d = slabScene();
        GpuRayCaster gpu(*volume_);
        const ImageRGBA8 without = gpu.render(d).image;
        gpu.setSurface(plain(box(boxLo_, boxHi_), red_));
        const ImageRGBA8 with = gpu.render(d).image;
        const ViewFrame f = makeViewFrame(volume_->geometry(), d.camera, d.width, d.height);
        const ScreenBox front = screenBox(d, {boxLo_, {boxHi_.x, boxLo_.y, boxHi_.z}});
        const ScreenBox all = screenBox(d, {boxLo_, boxHi_});
        int inside = 0, outside = 0, hidden = 0, wrong = 0;
        for (int y = 0; y < d.height; ++y) {
            for (int x = 0; x < d.width; ++x) {
                if (front.inside(x, y, 1.0)) {
                    const glm::dvec3 face =
                        lit(red_, {0, -1, 0}, f.rayDirection(x, y, d.width, d.height),
                            d.transferFunction.shading);
                    ++inside;
                    wrong += differenceAt(with, x, y, face) > 2;
                    hidden += differenceAt(without, x, y, face) > 20;
                } else if (!all.inside(x, y, -1.0)) {
                    ++outside;
                    wrong += differenceAt(with, without, x, y) > 1;
                }
            }
        }
        qInfo("box: %d pixels inside, %d outside, %d would show the slab", inside, outside, hidden);
        QVERIFY(inside > 200 && outside > 3000);
        QVERIFY(hidden > inside * 9 / 10);
        if (wrong > 0) {
            writePng(with, std::filesystem::path(LUCENT_BIN_DIR) / "gl_failed_box.png");
        }
        QCOMPARE(wrong, 0);

        // The eye inside a box: every ray stops at a back face (y = 25, whose normal points away).
        d.camera.distance = 2.0; // eye at y = 17.5
        gpu.setSurface(plain(box({12, 14, 12}, {27, 25, 27}), red_));
        const ImageRGBA8 enclosed = gpu.render(d).image;
        const ImageRGBA8 open = GpuRayCaster(*volume_).render(d).image;
        const ViewFrame g = makeViewFrame(volume_->geometry(), d.camera, d.width, d.height);
        wrong = hidden = 0;
        for (int y = 0; y < d.height; ++y) {
            for (int x = 0; x < d.width; ++x) {
                const glm::dvec3 back =
                    lit(red_, {0, 1, 0}, g.rayDirection(x, y, d.width, d.height),
                        d.transferFunction.shading);
                wrong += differenceAt(enclosed, x, y, back) > 2;
                hidden += differenceAt(open, x, y, back) > 20;
            }
        }
        QCOMPARE(wrong, 0);
        QVERIFY(hidden > d.width * d.height / 2); // the slab shows without the box
    }

    // (c) showVolume false: the surface over the background, no samples.
    void surfaceAlone() {
        const RenderDescription d = slabScene();
        GpuRayCaster gpu(*volume_);
        gpu.setSurface(plain(box(boxLo_, boxHi_), red_, false));
        const RenderResult r = gpu.render(d);
        QCOMPARE(r.stats.samples, std::size_t(0));
        const ViewFrame f = makeViewFrame(volume_->geometry(), d.camera, d.width, d.height);
        const ScreenBox front = screenBox(d, {boxLo_, {boxHi_.x, boxLo_.y, boxHi_.z}});
        const ScreenBox all = screenBox(d, {boxLo_, boxHi_});
        int inside = 0, outside = 0, wrong = 0;
        for (int y = 0; y < d.height; ++y) {
            for (int x = 0; x < d.width; ++x) {
                const float alpha = r.premultiplied[std::size_t(y) * d.width + x].a;
                if (front.inside(x, y, 1.0)) {
                    ++inside;
                    wrong +=
                        alpha != 1.0f ||
                        differenceAt(r.image, x, y,
                                     lit(red_, {0, -1, 0}, f.rayDirection(x, y, d.width, d.height),
                                         d.transferFunction.shading)) > 2;
                } else if (!all.inside(x, y, -1.0)) {
                    ++outside;
                    wrong += alpha != 0.0f || differenceAt(r.image, x, y, d.background) != 0;
                }
            }
        }
        QVERIFY(inside > 200 && outside > 3000);
        QCOMPARE(wrong, 0);
    }

    // (d) A field: bands of one value each across the view, below, at, in the
    // middle of, at and above [lo, hi]: viridis' ends, its middle, clamped.
    void fieldShowsViridisEnds() {
        const double values[] = {-1.0, 0.5, 1.5, 2.5, 7.0};
        const double t[] = {0.0, 0.0, 0.5, 1.0, 1.0};
        const double edges[] = {-200.0, 5.0, 15.0, 25.0, 35.0, 240.0}; // x of the bands
        auto mesh = std::make_shared<TriangleMesh>();
        auto field = std::make_shared<std::vector<float>>();
        for (int b = 0; b < 5; ++b) {
            const Mesh q = quadAt(10.0, edges[b], edges[b + 1]);
            const auto first = std::uint32_t(mesh->vertices.size());
            mesh->vertices.insert(mesh->vertices.end(), q->vertices.begin(), q->vertices.end());
            for (const glm::u32vec3& tri : q->triangles) {
                mesh->triangles.push_back(tri + first);
            }
            field->insert(field->end(), 4, float(values[b]));
        }
        auto display = std::make_shared<SurfaceDisplay>();
        display->mesh = mesh;
        display->field = field;
        display->fieldLo = 0.5;
        display->fieldHi = 2.5;
        display->showVolume = false;
        RenderDescription d = slabScene(128, 64);
        GpuRayCaster gpu(*volume_);
        gpu.setSurface(display);
        const ImageRGBA8 image = gpu.render(d).image;
        const ViewFrame f = makeViewFrame(volume_->geometry(), d.camera, d.width, d.height);
        for (int b = 0; b < 5; ++b) {
            const ScreenBox band = screenBox(d, {{std::max(edges[b], -5.0), 10.0, 0.0},
                                                 {std::min(edges[b + 1], 45.0), 10.0, 40.0}});
            const int x = int(std::lround(0.5 * (band.x0 + band.x1)));
            for (int y = 8; y < d.height - 8; y += 8) {
                const glm::dvec3 want =
                    lit(viridis(t[b]), {0, -1, 0}, f.rayDirection(x, y, d.width, d.height),
                        d.transferFunction.shading);
                QVERIFY2(differenceAt(image, x, y, want) <= 2,
                         qPrintable(QString("band %1 at (%2, %3)").arg(b).arg(x).arg(y)));
            }
        }
    }

    // (e) drawInPlace into a framebuffer (read with glReadPixels) equals
    // render()'s frame: the plane in the volume, the surface alone, and an
    // interactive frame stretched to the rectangle.
    void drawnInPlaceAsReadBack() {
        RenderDescription plane = describe(*volume_, layerTf(), 120);
        plane.height = 94;
        plane.background = {0.1, 0.2, 0.3};
        for (const bool volume : {true, false}) {
            GpuRayCaster gpu(*volume_);
            gpu.setSurface(plain(quadAt(kPlaneY, 0.0, 30.0, 5.0, 35.0), {0.9, 0.7, 0.4}, volume));
            TestFramebuffer fb(plane.width, plane.height);
            const RenderStats drawn = gpu.drawInPlace(plane, fb.whole());
            const ImageRGBA8 inPlace = fb.read();
            const RenderResult readBack = gpu.render(plane);
            QCOMPARE(drawn.samples, readBack.stats.samples);
            QCOMPARE(drawn.samples > 0, volume);
            QVERIFY(comparedPsnr(inPlace, readBack.image, volume ? "in_place" : "in_place_alone",
                                 50.0) >= 50.0);
            QVERIFY(maxDifference(inPlace, readBack.image) <= 1);
        }
        const RenderDescription still = slabScene(120, 96);
        InteractiveQuality quality;
        quality.imageScale = 0.5;
        const RenderDescription small = interactiveDescription(still, quality);
        QVERIFY(small.width < still.width);
        GpuRayCaster gpu(*volume_);
        gpu.setSurface(plain(box(boxLo_, boxHi_), red_));
        TestFramebuffer fb(still.width, still.height);
        gpu.drawInPlace(small, fb.whole());
        const ImageRGBA8 scaled = scaledTo(gpu.render(small).image, still.width, still.height);
        QVERIFY(comparedPsnr(fb.read(), scaled, "in_place_stretched", 50.0) >= 50.0);
        QVERIFY(maxDifference(fb.read(), scaled) <= 1);
    }

    // (f) A new display replaces the old (the mesh uploaded again only when it
    // is another one), null removes it, the kept frame is not drawn again;
    // parts refuse surfaces, the CPU ignores them, bad meshes are refused.
    void displaysReplaceEachOther() {
        const RenderDescription d = slabScene(96, 80);
        const auto fresh = [&](std::shared_ptr<const SurfaceDisplay> s) {
            GpuRayCaster other(*volume_);
            other.setSurface(std::move(s));
            return other.render(d).image;
        };
        const Mesh cube = box(boxLo_, boxHi_);
        const auto a = plain(cube, red_), blue = plain(cube, {0.2, 0.3, 0.9});
        const auto plane = plain(quadAt(28.0, 5.0, 20.0, 5.0, 30.0), {0.9, 0.9, 0.2});
        GpuRayCaster gpu(*volume_);
        gpu.setSurface(a);
        GpuRenderResult r = gpu.renderWithGpuStats(d);
        QCOMPARE(r.gpu.surfaceBytesUploaded,
                 24 * 6 * sizeof(float) + 12 * 3 * sizeof(std::uint32_t));
        const ImageRGBA8 imageA = r.frame.image;
        QCOMPARE(imageA, fresh(a));
        QCOMPARE(gpu.renderWithGpuStats(d).gpu.surfaceBytesUploaded, std::size_t(0));
        gpu.setSurface(blue); // the same mesh, another colour: nothing uploaded
        r = gpu.renderWithGpuStats(d);
        QCOMPARE(r.gpu.surfaceBytesUploaded, std::size_t(0));
        QVERIFY(psnr(r.frame.image, imageA) < 30.0);
        QCOMPARE(r.frame.image, fresh(blue));
        gpu.setSurface(plane);
        r = gpu.renderWithGpuStats(d);
        QVERIFY(r.gpu.surfaceBytesUploaded > 0);
        QCOMPARE(r.frame.image, fresh(plane));
        gpu.setSurface(nullptr);
        QCOMPARE(gpu.render(d).image, fresh(nullptr));

        // In place: a repaint after setSurface casts again.
        TestFramebuffer fb(d.width, d.height);
        gpu.setSurface(a);
        gpu.drawInPlace(d, fb.whole());
        QVERIFY(maxDifference(fb.read(), imageA) <= 1);
        gpu.setSurface(plane);
        gpu.drawInPlace(d, fb.whole());
        QVERIFY(maxDifference(fb.read(), fresh(plane)) <= 1);

        const VolumePart whole{volume_->geometry(),
                               {0, 0, 0},
                               {{0, 0, 0}, volume_->dims() - 1},
                               volume_->valueRange()};
        GpuRayCaster part(*volume_, whole);
        QVERIFY_THROWS_EXCEPTION(std::logic_error, part.setSurface(a));
        QVERIFY(!CpuRayCaster(*volume_).setSurface(a));
        auto broken = std::make_shared<SurfaceDisplay>(*a);
        auto bad = std::make_shared<TriangleMesh>(*cube);
        bad->triangles.push_back({0, 1, 24});
        broken->mesh = bad;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, gpu.setSurface(broken));
        broken->mesh = cube;
        broken->field = std::make_shared<std::vector<float>>(23, 0.0f);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, gpu.setSurface(broken));
    }

    // LocalRenderBackend keeps the surface, gives it to the GL renderer
    // (again when it is reopened) and says the CPU renderer does not show it.
    void backendKeepsTheSurface() {
        const RenderDescription d = slabScene(96, 80);
        const auto a = plain(box(boxLo_, boxHi_), red_);
        GpuRayCaster gpu(*volume_);
        gpu.setSurface(a);
        const ImageRGBA8 withSurface = gpu.render(d).image;
        LocalRenderBackend backend;
        ImageRGBA8 got;
        QObject::connect(&backend, &RenderBackend::frameReady,
                         [&](const BackendFrame& frame) { got = frame.image; });
        const auto frameOf = [&] {
            got = {};
            backend.request(d, {});
            backend.renderPending();
            return got;
        };
        backend.setVolume(volume_);
        backend.setKind(RendererKind::Gl);
        QVERIFY(!backend.surfaceShown());
        backend.setSurface(a);
        QVERIFY(backend.surfaceShown());
        QCOMPARE(frameOf(), withSurface);
        backend.releaseGl();
        backend.setKind(RendererKind::Cpu);
        QCOMPARE(frameOf(), CpuRayCaster(*volume_).render(d).image);
        QVERIFY(!backend.surfaceShown());
        backend.setKind(RendererKind::Gl);
        QCOMPARE(frameOf(), withSurface);
        QVERIFY(backend.surfaceShown());
        backend.setSurface(nullptr);
        QVERIFY(!backend.surfaceShown());
        QCOMPARE(frameOf(), GpuRayCaster(*volume_).render(d).image);
        backend.releaseGl();
    }
};

QTEST_GUILESS_MAIN(TestSurfaceInVolume)
#include "test_surface_in_volume.moc"
