// What the ray caster's accelerations must not change: empty-space leaping,
// brick and cell sizes, the fast and SIMD kernels, tables kept between frames.
#include <QTest>

#include <cmath>
#include <random>
#include <string>

#include "core/raycast/CpuRayCaster.h"
#include "core/raycast/LeapReach.h"
#include "tests/core/raycast/RaycastScenes.h"

using namespace lucent;
using namespace lucent::test;

class TestRayKernels : public QObject {
    Q_OBJECT
private slots:
    void emptySpaceLeapingChangesNoPixel_data() {
        QTest::addColumn<int>("mode");
        QTest::addColumn<int>("interp");
        QTest::newRow("dvr-linear") << int(RenderMode::Dvr) << int(Interpolation::Linear);
        QTest::newRow("dvr-cubic") << int(RenderMode::Dvr) << int(Interpolation::Cubic);
        QTest::newRow("dvr-nearest") << int(RenderMode::Dvr) << int(Interpolation::Nearest);
        QTest::newRow("iso-linear") << int(RenderMode::Isosurface) << int(Interpolation::Linear);
        QTest::newRow("mip-linear") << int(RenderMode::Mip) << int(Interpolation::Linear);
        QTest::newRow("minip-linear") << int(RenderMode::MinIp) << int(Interpolation::Linear);
    }
    void emptySpaceLeapingChangesNoPixel() {
        QFETCH(int, mode);
        QFETCH(int, interp);
        const Volume v = makeVolume({40, 40, 36}, blobs, VoxelType::Int16);
        RenderDescription d = describe(v, rampTf(true), 64);
        d.mode = RenderMode(mode);
        d.isoValue = 100.0;
        d.sampling.interpolation = Interpolation(interp);
        d.sampling.brickSize = 8;
        CpuRayCaster caster(v);
        const RenderResult leaping = caster.render(d);
        d.sampling.emptySpaceLeaping = false;
        const RenderResult every = caster.render(d);
        QVERIFY(leaping.premultiplied == every.premultiplied);
        QVERIFY2(
            leaping.stats.samples < every.stats.samples,
            qPrintable(QString("%1 vs %2").arg(leaping.stats.samples).arg(every.stats.samples)));
        QVERIFY(leaping.stats.bricksUsed < leaping.stats.bricksTotal ||
                mode == int(RenderMode::Mip) || mode == int(RenderMode::MinIp));
    }

    void brickSizeDoesNotChangeTheImage() {
        const Volume v = makeVolume({50, 44, 40}, blobs, VoxelType::Int16);
        RenderDescription d = describe(v, rampTf(true), 64);
        d.sampling.interpolation = Interpolation::Cubic;
        CpuRayCaster caster(v);
        d.sampling.emptySpaceLeaping = false;
        const RenderResult unbricked = caster.render(d);
        d.sampling.emptySpaceLeaping = true;
        for (const int size : {16, 32, 64, 128}) {
            d.sampling.brickSize = size;
            QVERIFY2(caster.render(d).premultiplied == unbricked.premultiplied,
                     qPrintable(QString::number(size)));
        }
    }

    void fastKernelAgreesWithTheGenericOne_data() {
        QTest::addColumn<int>("type");
        QTest::addColumn<bool>("shading");
        QTest::newRow("int16-shaded") << int(VoxelType::Int16) << true;
        QTest::newRow("uint16-shaded") << int(VoxelType::UInt16) << true;
        QTest::newRow("float-unshaded") << int(VoxelType::Float32) << false;
    }
    void fastKernelAgreesWithTheGenericOne() {
        QFETCH(int, type);
        QFETCH(bool, shading);
        const Volume v = facesAndBlobs(VoxelType(type));
        RenderDescription d = describe(v, rampTf(shading), 72);
        d.camera.azimuth = 25.0;
        d.camera.elevation = 15.0;
        CpuRayCaster caster(v);
        d.sampling.brickSize = 6; // leap cells of 6: not a power of two, the generic kernel
        const RenderResult generic = caster.render(d);
        for (const int size : {8, 16, 64}) { // leap cells of 8: the fast kernel
            d.sampling.brickSize = size;
            const RenderResult fast = caster.render(d);
            const float worst = maxDifference(fast.premultiplied, generic.premultiplied);
            QVERIFY2(worst < 1e-4f,
                     qPrintable(QString("brick %1: max difference %2").arg(size).arg(worst)));
        }
    }

    void packetKernelAgreesWithTheScalarOne_data() {
        QTest::addColumn<int>("type");
        QTest::addColumn<bool>("shading");
        QTest::newRow("int16-shaded") << int(VoxelType::Int16) << true;
        QTest::newRow("uint16-shaded") << int(VoxelType::UInt16) << true;
        QTest::newRow("float-shaded") << int(VoxelType::Float32) << true;
        QTest::newRow("int16-unshaded") << int(VoxelType::Int16) << false;
    }
    void packetKernelAgreesWithTheScalarOne() {
        QFETCH(int, type);
        QFETCH(bool, shading);
        // SIMD packets of eight rays (where the CPU has AVX2) against the scalar
        // kernel (sampling.simd = false): structure on every face, a width that
        // leaves a partial packet per row, leaping on and off, a clip box.
        const Volume v = facesAndBlobs(VoxelType(type));
        RenderDescription d = describe(v, rampTf(shading), 70);
        d.camera.azimuth = 25.0;
        d.camera.elevation = 15.0;
        d.sampling.earlyTermination = 0.9;
        CpuRayCaster caster(v);
        for (const bool clip : {false, true}) {
            d.clip.lo = clip ? glm::dvec3(3.5, 2.0, 4.25) : glm::dvec3(-1e9);
            for (const int size : {8, 16, 64}) {
                for (const bool leap : {true, false}) {
                    d.sampling.brickSize = size;
                    d.sampling.emptySpaceLeaping = leap;
                    d.sampling.simd = false;
                    const RenderResult scalar = caster.render(d);
                    d.sampling.simd = true;
                    const RenderResult packet = caster.render(d);
                    const float worst = maxDifference(packet.premultiplied, scalar.premultiplied);
                    QVERIFY2(worst < 1e-4f, qPrintable(QString("clip %1 brick %2 leap %3: %4")
                                                           .arg(clip)
                                                           .arg(size)
                                                           .arg(leap)
                                                           .arg(worst)));
                    QCOMPARE(packet.stats.samples, scalar.stats.samples);
                }
            }
        }
    }

    void leapReachIsTheChessboardDistanceToWhatCannotBeLeapt() {
        std::mt19937 rng(7);
        for (int trial = 0; trial < 20; ++trial) {
            const glm::ivec3 n(1 + int(rng() % 9), 1 + int(rng() % 9), 1 + int(rng() % 9));
            std::vector<std::uint8_t> leapable(std::size_t(n.x) * n.y * n.z);
            for (std::uint8_t& v : leapable) {
                v = rng() % 10 < 8 ? 1 : 0;
            }
            const std::vector<std::uint8_t> reach = leapReach(leapable, n);
            std::size_t c = 0;
            for (int z = 0; z < n.z; ++z) {
                for (int y = 0; y < n.y; ++y) {
                    for (int x = 0; x < n.x; ++x, ++c) {
                        // Brute force: the nearest cell that cannot be leapt, less one.
                        int nearest = 255;
                        std::size_t o = 0;
                        for (int k = 0; k < n.z; ++k) {
                            for (int j = 0; j < n.y; ++j) {
                                for (int i = 0; i < n.x; ++i, ++o) {
                                    if (leapable[o] == 0) {
                                        nearest = std::min(
                                            nearest, std::max({std::abs(i - x), std::abs(j - y),
                                                               std::abs(k - z)}));
                                    }
                                }
                            }
                        }
                        const int expected = leapable[c] == 0 ? 0 : std::min(nearest - 1, 254);
                        QCOMPARE(int(reach[c]), expected);
                    }
                }
            }
        }
    }

    // The capped reach (erosions) is the exact reach (the distance transform), capped.
    void leapReachWithinIsLeapReachCapped() {
        std::mt19937 rng(11);
        for (int trial = 0; trial < 20; ++trial) {
            // Rows of more than one 64-bit word too.
            const glm::ivec3 n(1 + int(rng() % 150), 1 + int(rng() % 12), 1 + int(rng() % 12));
            std::vector<std::uint8_t> leapable(std::size_t(n.x) * n.y * n.z);
            for (std::uint8_t& v : leapable) {
                v = rng() % 20 < 19 ? 1 : 0;
            }
            const std::vector<std::uint8_t> exact = leapReach(leapable, n);
            for (const int cap : {1, 3, 5, 40}) {
                std::vector<std::uint8_t> expected = exact;
                for (std::uint8_t& r : expected) {
                    r = std::uint8_t(std::min(int(r), cap));
                }
                QVERIFY(leapReachWithin(leapable, n, cap) == expected);
            }
        }
    }

    void changesBetweenFramesMatchAFreshCaster() {
        const Volume v = makeVolume({40, 37, 35}, blobs);
        CpuRayCaster kept(v);
        TransferFunction narrow = rampTf(true);
        narrow.opacity = {{120.0, 0.0}, {160.0, 0.5}};
        std::vector<RenderDescription> frames;
        for (const TransferFunction& tf : {rampTf(true), narrow, rampTf(false), rampTf(true)}) {
            RenderDescription d = describe(v, tf, 41);
            d.sampling.step = 0.5;
            frames.push_back(d);
        }
        frames.push_back(frames[0]);
        frames.back().sampling.step = 0.25;
        frames.push_back(frames[0]);
        frames.back().sampling.brickSize = 16;
        frames.push_back(frames[1]);
        frames.back().mode = RenderMode::Isosurface;
        frames.back().isoValue = 100.0;
        frames.push_back(frames[1]);
        frames.back().isoValue = 150.0;
        frames.back().mode = RenderMode::Isosurface;
        frames.push_back(frames[0]);
        for (std::size_t n = 0; n < frames.size(); ++n) {
            RenderDescription& d = frames[n];
            d.camera.azimuth = 10.0 * double(n);
            const RenderResult a = kept.render(d);
            const RenderResult b = CpuRayCaster(v).render(d);
            QVERIFY2(a.premultiplied == b.premultiplied, qPrintable(QString::number(n)));
            QCOMPARE(a.stats.samples, b.stats.samples);
            QCOMPARE(a.stats.bricksUsed, b.stats.bricksUsed);
        }
    }

    void frameDetailsSplitTheFrameIntoCastAndTheRest() {
        // The caster reports what a frame spent on its rays and outside them;
        // a fresh caster's first frame (tables, leap data) costs more outside
        // the cast than a camera-only change after it.
        const Volume v = makeVolume({48, 44, 40}, blobs);
        CpuRayCaster caster(v);
        RenderDescription d = describe(v, rampTf(true), 64);
        const auto figure = [&](const std::string& key) {
            const std::optional<std::string> value = frameDetail(caster.frameDetails(), key);
            return value ? std::stod(*value) : -1.0;
        };
        QCOMPARE(figure("cast_ms"), 0.0); // no frame yet
        caster.render(d);
        const double firstOutside = figure("outside_cast_ms");
        QVERIFY(figure("cast_ms") > 0.0);
        double moved = HUGE_VAL;
        for (int n = 1; n <= 3; ++n) { // the least of three: one stall does not decide
            d.camera.azimuth = 10.0 * n;
            caster.render(d);
            moved = std::min(moved, figure("outside_cast_ms"));
            QVERIFY(figure("cast_ms") > 0.0);
        }
        QVERIFY2(moved >= 0.0 && moved < firstOutside,
                 qPrintable(QString("%1 vs %2 ms").arg(moved).arg(firstOutside)));
    }
};

QTEST_APPLESS_MAIN(TestRayKernels)
#include "test_ray_kernels.moc"
