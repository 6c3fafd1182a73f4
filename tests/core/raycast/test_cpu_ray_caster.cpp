// The CPU reference ray caster against closed forms: opacity of slabs and
// chords, MIP, isosurface discs, convergence, camera conventions, presets.
#include <QTest>

#include <algorithm>
#include <numbers>
#include <random>
#include <set>
#include <string>

#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/scene/ViewFrame.h"
#include "core/volume/VolumePart.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/support/RealData.h"

using namespace lucent;
using namespace lucent::test;

namespace {
const char* const kPhilipsS2010 = "dcm_qa_ct/Philips_S21570/S2010";
} // namespace

class TestCpuRayCaster : public QObject {
    Q_OBJECT
private slots:
    void slabOpacityHasTheClosedForm_data() {
        QTest::addColumn<int>("precision");
        QTest::addColumn<int>("classification");
        QTest::addColumn<bool>("preintegrate");
        QTest::newRow("float-post") << int(Precision::Float) << int(Classification::Post) << false;
        QTest::newRow("double-post")
            << int(Precision::Double) << int(Classification::Post) << false;
        QTest::newRow("float-pre") << int(Precision::Float) << int(Classification::Pre) << false;
        QTest::newRow("float-preintegrated")
            << int(Precision::Float) << int(Classification::Post) << true;
    }
    void slabOpacityHasTheClosedForm() {
        QFETCH(int, precision);
        QFETCH(int, classification);
        QFETCH(bool, preintegrate);
        // 33 voxels of constant value: the centre ray crosses 32 mm of constant extinction.
        const Volume v = makeVolume({33, 33, 33}, [](int, int, int) { return 100.0; });
        const double a0 = 0.05;
        const double closed = 1.0 - std::pow(1.0 - a0, 32.0);
        double previousError = 1.0;
        for (const double step : {1.0, 0.5, 0.25, 0.125}) {
            RenderDescription d = describe(v, flatTf(a0));
            d.sampling.step = step;
            d.sampling.precision = Precision(precision);
            d.sampling.classification = Classification(classification);
            d.sampling.preintegrate = preintegrate;
            d.sampling.earlyTermination = 1.0;
            const RenderResult r = CpuRayCaster(v).render(d);
            const double a = r.premultiplied[16 * 33 + 16].a;
            // Samples at both ends of [0, 32]: a Riemann sum over 32 + step mm
            // (pre-integration: over the segments between samples, exactly 32 mm).
            const double lengthSampled = preintegrate ? 32.0 : 32.0 + step;
            const double discrete = 1.0 - std::pow(1.0 - a0, lengthSampled);
            QVERIFY2(std::abs(a - discrete) < 2e-5,
                     qPrintable(QString("step %1: %2 vs %3").arg(step).arg(a).arg(discrete)));
            const double error = std::abs(a - closed);
            QVERIFY(error <= previousError + 1e-7);
            previousError = error;
        }
        QVERIFY(previousError < (preintegrate ? 1e-4 : 0.003));
    }

    void sphereChordsHaveTheClosedForm() {
        // A ball of radius 12 voxels: each ray's opacity follows its chord length.
        const glm::dvec3 c(20, 20, 20);
        const double radius = 12.0;
        const Volume v = makeVolume({41, 41, 41}, [&](int i, int j, int k) {
            return glm::length(glm::dvec3(i, j, k) - c) <= radius ? 100.0 : 0.0;
        });
        TransferFunction tf = flatTf(0.0);
        tf.opacity = {{0.0, 0.0}, {99.0, 0.0}, {100.0, 0.04}};
        constexpr int size = 81;
        RenderDescription d = describe(v, tf, size);
        d.sampling.step = 0.25;
        d.sampling.interpolation = Interpolation::Nearest;
        d.sampling.earlyTermination = 1.0;
        const RenderResult r = CpuRayCaster(v).render(d);
        const ViewFrame frame = makeViewFrame(v.geometry(), d.camera, size, size);
        int checked = 0;
        for (int y = 0; y < size; ++y) {
            for (int x = 0; x < size; ++x) {
                const glm::dvec3 w = frame.rayDirection(x, y, size, size);
                const glm::dvec3 toCentre = c - frame.eye;
                const double b = glm::length(toCentre - w * glm::dot(toCentre, w));
                if (b > radius - 1.5) {
                    continue; // near the rim the voxel staircase dominates
                }
                const double chord = 2.0 * std::sqrt(radius * radius - b * b);
                const double expected = 1.0 - std::pow(1.0 - 0.04, chord);
                const double a = r.premultiplied[std::size_t(y) * size + x].a;
                // Nearest voxels make the chord uncertain by about one voxel at each end.
                const double slack = 1.0 - std::pow(1.0 - 0.04, 2.0);
                QVERIFY2(std::abs(a - expected) <= slack,
                         qPrintable(
                             QString("pixel %1,%2: %3 vs %4").arg(x).arg(y).arg(a).arg(expected)));
                ++checked;
            }
        }
        QVERIFY(checked > 40);
    }

    void mipFindsTheKnownMaximum() {
        std::mt19937 rng(5);
        std::uniform_int_distribution<int> u(0, 1000);
        Volume v = makeVolume(
            {40, 30, 24}, [&](int, int, int) { return u(rng); }, VoxelType::Int16);
        v.voxels<std::int16_t>()[v.linearIndex(20, 12, 10)] = 3000;
        TransferFunction tf;
        tf.opacity = {{0.0, 1.0}, {4000.0, 1.0}};
        tf.colour = {{0.0, {0, 0, 0}}, {4000.0, {1, 1, 1}}};
        tf.shading.enabled = false;
        RenderDescription d = describe(v, tf, 64);
        d.mode = RenderMode::Mip;
        d.sampling.interpolation = Interpolation::Nearest;
        d.sampling.step = 0.25;
        d.sampling.precision = Precision::Double;
        const RenderResult r = CpuRayCaster(v).render(d);
        double brightest = 0.0;
        for (const glm::vec4& p : r.premultiplied) {
            brightest = std::max(brightest, double(p.r));
        }
        QVERIFY2(std::abs(brightest - 0.75) < 1e-6, qPrintable(QString::number(brightest)));
        d.sampling.emptySpaceLeaping = false;
        const RenderResult all = CpuRayCaster(v).render(d);
        QVERIFY(all.premultiplied == r.premultiplied);
    }

    void isosurfaceOfASphereIsADiscOfTheRightRadius() {
        const glm::dvec3 c(24, 24, 24);
        const Volume v = makeVolume({49, 49, 49}, [&](int i, int j, int k) {
            return 100.0 - glm::length(glm::dvec3(i, j, k) - c); // 90 on a sphere of radius 10
        });
        RenderDescription d = describe(v, rampTf(true), 101);
        d.mode = RenderMode::Isosurface;
        d.isoValue = 90.0;
        d.sampling.step = 0.5;
        const RenderResult r = CpuRayCaster(v).render(d);
        int hits = 0;
        for (const glm::vec4& p : r.premultiplied) {
            hits += p.a > 0.5f ? 1 : 0;
        }
        // Perspective: the silhouette's half angle is asin(R / D).
        const ViewFrame frame = makeViewFrame(v.geometry(), d.camera, 101, 101);
        const double dist = glm::length(c - frame.eye);
        const double rPx = std::tan(std::asin(10.0 / dist)) / frame.tanHalfFov * 50.5;
        const double expected = std::numbers::pi * rPx * rPx;
        QVERIFY2(std::abs(hits - expected) < 0.03 * expected,
                 qPrintable(QString("%1 pixels, expected %2").arg(hits).arg(expected)));
        // Head-on the surface faces the light: the centre is the brightest point.
        const float centre = r.premultiplied[50 * 101 + 50].g;
        for (const glm::vec4& p : r.premultiplied) {
            QVERIFY(p.g <= centre + 1e-4f);
        }
    }

    void errorFallsAsTheStepShrinks() {
        const Volume v = makeVolume({40, 40, 36}, blobs, VoxelType::Int16);
        CpuRayCaster caster(v);
        RenderDescription ref = describe(v, rampTf(true), 64);
        ref.sampling.step = 1.0 / 16.0;
        ref.sampling.interpolation = Interpolation::Cubic;
        ref.sampling.precision = Precision::Double;
        ref.sampling.earlyTermination = 1.0;
        const ImageRGBA8 reference = toImage(caster.render(ref).premultiplied, 64, 64);
        double previous = 0.0;
        for (const double step : {2.0, 1.0, 0.5, 0.25}) {
            RenderDescription d = ref;
            d.sampling.step = step;
            const double p = psnr(toImage(caster.render(d).premultiplied, 64, 64), reference);
            QVERIFY2(
                p > previous,
                qPrintable(QString("step %1: %2 dB after %3 dB").arg(step).arg(p).arg(previous)));
            previous = p;
        }
        QVERIFY(previous > 40.0);
    }

    void anteriorViewHeadUpPatientLeftOnScreenRight() {
        // Markers: patient's left (+x) and head (+z).
        const Volume v = makeVolume({41, 41, 41}, [](int i, int j, int k) {
            const bool left = i > 32 && std::abs(j - 20) < 4 && std::abs(k - 20) < 4;
            const bool head = k > 32 && std::abs(i - 20) < 4 && std::abs(j - 20) < 4;
            return left ? 100.0 : head ? 200.0 : 0.0;
        });
        TransferFunction tf;
        tf.opacity = {{0.0, 0.0}, {50.0, 1.0}};
        tf.colour = {{100.0, {1, 0, 0}}, {200.0, {0, 0, 1}}};
        tf.shading.enabled = false;
        RenderDescription d = describe(v, tf, 64);
        d.sampling.interpolation = Interpolation::Nearest;
        auto centroid = [](const RenderResult& r, int channel) {
            glm::dvec2 sum(0.0);
            double n = 0;
            for (int y = 0; y < 64; ++y) {
                for (int x = 0; x < 64; ++x) {
                    if (r.premultiplied[std::size_t(y) * 64 + x][channel] > 0.5f) {
                        sum += glm::dvec2(x, y);
                        ++n;
                    }
                }
            }
            return n > 0 ? sum / n : glm::dvec2(-1);
        };
        const RenderResult front = CpuRayCaster(v).render(d);
        const glm::dvec2 left = centroid(front, 0), head = centroid(front, 2);
        QVERIFY2(left.x > 40 && std::abs(left.y - 31.5) < 3,
                 qPrintable(QString("%1,%2").arg(left.x).arg(left.y)));
        QVERIFY2(head.y < 24 && std::abs(head.x - 31.5) < 3,
                 qPrintable(QString("%1,%2").arg(head.x).arg(head.y)));
        // Azimuth 90 turns about the head-foot axis: the head stays up, the left marker moves to
        // the centre line.
        d.camera.azimuth = 90.0;
        const RenderResult turned = CpuRayCaster(v).render(d);
        QVERIFY(std::abs(centroid(turned, 0).x - 31.5) < 3);
        QVERIFY(centroid(turned, 2).y < 24);
        // Elevation 90 looks from below or above: the head marker comes to the centre.
        d.camera.azimuth = 0.0;
        d.camera.elevation = 90.0;
        const glm::dvec2 raised = centroid(CpuRayCaster(v).render(d), 2);
        QVERIFY2(glm::length(raised - glm::dvec2(31.5)) < 3,
                 qPrintable(QString("%1,%2").arg(raised.x).arg(raised.y)));
    }

    void presetsRenderRealCt() {
        REQUIRE_DATA(kPhilipsS2010);
        const Volume v = loadPath(kRealData / kPhilipsS2010);
        CpuRayCaster caster(v);
        for (const std::string& name : presetNames()) {
            RenderDescription d = describe(v, loadPreset(name), 96);
            d.mode = name == "ct-mip" ? RenderMode::Mip : RenderMode::Dvr;
            const RenderResult r = caster.render(d);
            int lit = 0;
            std::set<std::uint32_t> colours;
            for (int n = 0; n < 96 * 96; ++n) {
                const std::uint8_t* p = &r.image.pixels[std::size_t(n) * 4];
                lit += (p[0] | p[1] | p[2]) != 0 ? 1 : 0;
                colours.insert(std::uint32_t(p[0]) << 16 | std::uint32_t(p[1]) << 8 | p[2]);
            }
            QVERIFY2(lit > 96 * 96 / 20 && colours.size() > 20,
                     qPrintable(QString("%1: %2 lit pixels, %3 colours")
                                    .arg(QString::fromStdString(name))
                                    .arg(lit)
                                    .arg(colours.size())));
        }
    }

    // One caster keeps what a render derived from the transfer function and
    // the step (tables, pre-integration, leaping): frames that change them in
    // turn equal those of a fresh caster.
    void derivedTablesFollowEachChange() {
        REQUIRE_DATA(kPhilipsS2010);
        const Volume v = loadPath(kRealData / kPhilipsS2010);
        CpuRayCaster kept(v);
        std::vector<RenderDescription> views;
        for (const char* preset : {"ct-soft-tissue", "ct-bone"}) {
            for (const double step : {0.5, 1.0}) {
                RenderDescription d = describe(v, loadPreset(preset), 64);
                d.sampling.preintegrate = true;
                d.sampling.step = step;
                views.push_back(d);
            }
        }
        views.push_back(views.front());
        for (const RenderDescription& d : views) {
            CpuRayCaster fresh(v);
            QVERIFY(kept.render(d).image == fresh.render(d).image);
        }
    }

    // Frames handed back (recycle) lend their buffers to the next frame of their
    // size, which is not cleared: every pixel must be written again. A close
    // view that fills the image, then a far one and a clipped one whose rays
    // cover less of it, then another size: each equal to a fresh caster's
    // (image and premultiplied colours), on the real CT through the SIMD kernel.
    void handedBackFramesEqualFreshOnes() {
        REQUIRE_DATA(kPhilipsS2010);
        const Volume v = loadPath(kRealData / kPhilipsS2010);
        RenderDescription close = describe(v, loadPreset("ct-soft-tissue"), 96);
        close.camera.zoom = 3.0;
        RenderDescription far = close;
        far.camera.zoom = 0.6;
        far.camera.azimuth = 30.0;
        RenderDescription clipped = far;
        clipped.clip.hi = glm::dvec3(v.dims()) * 0.5;
        RenderDescription other = far;
        other.width = 80;
        CpuRayCaster kept(v);
        const auto buffers = [&] {
            return frameDetail(kept.frameDetails(), "frame_buffers").value_or("(none)");
        };
        // frame_buffers: the first frame and one of another size get new ones.
        const char* expected[] = {"new", "recycled", "recycled", "recycled", "new", "new"};
        int n = 0;
        for (const RenderDescription* d : {&close, &far, &clipped, &close, &other, &far}) {
            RenderResult r = kept.render(*d);
            QCOMPARE(buffers(), std::string(expected[n++]));
            const RenderResult fresh = CpuRayCaster(v).render(*d);
            QVERIFY(r.image == fresh.image);
            QVERIFY(r.premultiplied == fresh.premultiplied);
            kept.recycle(std::move(r));
        }
        // A part the clip box leaves out draws nothing, into a handed-back frame too.
        const PartBox box{{0, 0, 0}, v.dims() / 2};
        const VolumePart where{v.geometry(), glm::ivec3(0), box, v.valueRange()};
        const Volume part = cutPart(v, glm::ivec3(0), v.dims() / 2 + 2);
        CpuRayCaster partCaster(part, where);
        RenderDescription inside = close;
        inside.volume = nullptr; // the part's caster renders its own voxels
        partCaster.recycle(partCaster.render(inside));
        RenderDescription outside = inside;
        outside.clip.lo = glm::dvec3(v.dims()) * 0.75;
        const RenderResult none = partCaster.render(outside);
        QVERIFY(std::all_of(none.image.pixels.begin(), none.image.pixels.end(),
                            [](std::uint8_t b) { return b == 0; }));
        QVERIFY(std::all_of(none.premultiplied.begin(), none.premultiplied.end(),
                            [](const glm::vec4& c) { return c == glm::vec4(0.0f); }));
    }

    void clipBoxRemovesWhatLiesOutside() {
        // Two blobs side by side along x; a clip box keeping x <= 19 removes the right one.
        const Volume v = makeVolume({40, 24, 24}, [](int i, int j, int k) {
            const double l = glm::length(glm::dvec3(i - 10, j - 12, k - 12));
            const double r = glm::length(glm::dvec3(i - 30, j - 12, k - 12));
            return l < 6 ? 120.0 : r < 6 ? 140.0 : 0.0;
        });
        RenderDescription d = describe(v, rampTf(false), 64);
        CpuRayCaster caster(v);
        const RenderResult whole = caster.render(d);
        d.clip.hi.x = 19.0;
        const RenderResult clipped = caster.render(d);
        auto opacityOnSide = [](const RenderResult& r, bool right) {
            double sum = 0.0;
            for (int y = 0; y < 64; ++y) {
                for (int x = right ? 32 : 0; x < (right ? 64 : 32); ++x) {
                    sum += r.premultiplied[std::size_t(y) * 64 + x].a;
                }
            }
            return sum;
        };
        QVERIFY(opacityOnSide(whole, true) > 10.0);
        QCOMPARE(opacityOnSide(clipped, true), 0.0); // screen right is patient left, +x
        QVERIFY(std::abs(opacityOnSide(clipped, false) - opacityOnSide(whole, false)) < 1e-3);
        QVERIFY(clipped.stats.bricksUsed <= whole.stats.bricksUsed);
        // A clip box that holds everything changes nothing.
        d.clip.lo = glm::dvec3(-5.0);
        d.clip.hi = glm::dvec3(100.0);
        QVERIFY(caster.render(d).premultiplied == whole.premultiplied);
    }

    // The caster keeps tables and leap decisions between frames: a change of
    // transfer function, step, mode or brick size must not render from stale ones.
    void badSettingsAreRejected() {
        const Volume v = makeVolume({4, 4, 4}, [](int, int, int) { return 0.0; });
        CpuRayCaster caster(v);
        const auto rejects = [&](const std::function<void(RenderDescription&)>& change) {
            RenderDescription d = describe(v, flatTf(0.1));
            change(d);
            try {
                caster.render(d);
            } catch (const std::invalid_argument&) {
                return true;
            }
            return false;
        };
        QVERIFY(rejects([](RenderDescription& d) { d.width = 0; }));
        QVERIFY(rejects([](RenderDescription& d) { d.width = d.height = 100000; }));
        QVERIFY(rejects([](RenderDescription& d) { d.sampling.step = 0.0; }));
        QVERIFY(rejects([](RenderDescription& d) { d.sampling.step = -1.0; }));
        QVERIFY(rejects([](RenderDescription& d) { d.sampling.step = std::nan(""); }));
        QVERIFY(rejects([](RenderDescription& d) { d.camera.zoom = 0.0; }));
        QVERIFY(rejects([](RenderDescription& d) { d.sampling.brickSize = 0; }));
        QVERIFY(rejects([](RenderDescription& d) {
            d.sampling.classification = Classification::Pre;
            d.sampling.interpolation = Interpolation::Cubic;
        }));
        QVERIFY(!rejects([](RenderDescription& d) {
            d.sampling.step = 1e-3;
            d.width = d.height = 2;
        }));
    }
};

QTEST_APPLESS_MAIN(TestCpuRayCaster)
#include "test_cpu_ray_caster.moc"
