// The MPR tools in core/mpr: window presets, thick slabs over known structures,
// and ellipse ROI statistics on the resliced plane (uniform disc, ramp).
#include <QTest>

#include <cmath>
#include <numbers>

#include "core/mpr/PlaneSampler.h"
#include "core/mpr/RoiStatistics.h"
#include "core/mpr/WindowPresets.h"

using namespace lucent;

namespace {

VolumeGeometry cube(int n, const glm::dvec3& spacing) {
    VolumeGeometry g;
    g.dims = {n, n, n};
    g.spacing = spacing;
    g.origin = {-50.0, 20.0, -100.0};
    return g;
}

template <class F> Volume fill(const VolumeGeometry& g, F&& valueAt) {
    Volume volume(g, VoxelType::Float32);
    auto voxels = volume.voxels<float>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                voxels[volume.linearIndex(i, j, k)] = static_cast<float>(
                    valueAt(glm::ivec3(i, j, k), g.toPatient(glm::dvec3(i, j, k))));
            }
        }
    }
    return volume;
}

} // namespace

class TestMprTools : public QObject {
    Q_OBJECT

private slots:
    void presetWindows();
    void slabOverKnownPlanes_data();
    void slabOverKnownPlanes();
    void roiOverUniformDisc();
    void roiOverRamp_data();
    void roiOverRamp();
    void roiEdgeCases();
};

void TestMprTools::presetWindows() {
    QCOMPARE(windowPresets().size(), std::size_t(8));
    const WindowPreset* lung = findWindowPreset("Lung");
    QVERIFY(lung);
    QCOMPARE(lung->width, 1500.0);
    QCOMPARE(lung->center, -600.0);
    QCOMPARE(findWindowPreset("Brain")->width, 80.0);
    QCOMPARE(findWindowPreset("Bone")->center, 400.0);
    QCOMPARE(windowPresets()[0].name, std::string_view("Brain"));
    QCOMPARE(windowPresets()[7].name, std::string_view("Bone"));
    QVERIFY(!findWindowPreset("lung"));
}

void TestMprTools::slabOverKnownPlanes_data() {
    QTest::addColumn<double>("thickness");
    QTest::addColumn<int>("mode");
    QTest::addColumn<double>("expected");
    // Axial voxel planes: k = 12 holds 100, k = 8 holds -50, the rest 0; the slab is
    // centred on k = 10 and the voxels are 2.5 mm apart along z.
    QTest::newRow("mip 10 mm") << 10.0 << int(SlabMode::Mip) << 100.0;
    QTest::newRow("minip 10 mm") << 10.0 << int(SlabMode::MinIp) << -50.0;
    QTest::newRow("average 10 mm") << 10.0 << int(SlabMode::Average) << (100.0 - 50.0) / 5.0;
    QTest::newRow("mip 5 mm misses both") << 5.0 << int(SlabMode::Mip) << 0.0;
    QTest::newRow("minip 5 mm misses both") << 5.0 << int(SlabMode::MinIp) << 0.0;
    QTest::newRow("thin") << 0.0 << int(SlabMode::Mip) << 0.0;
}

void TestMprTools::slabOverKnownPlanes() {
    QFETCH(double, thickness);
    QFETCH(int, mode);
    QFETCH(double, expected);
    const VolumeGeometry g = cube(21, {0.8, 0.8, 2.5});
    const Volume volume = fill(g, [](const glm::ivec3& ijk, const glm::dvec3&) {
        return ijk.z == 12 ? 100.0 : ijk.z == 8 ? -50.0 : 0.0;
    });
    SlicePlane plane = standardPlane(g, Orientation::Axial, g.toPatient({10, 10, 10}), 7, 7);
    plane.slabThickness = thickness;
    plane.slabMode = static_cast<SlabMode>(mode);
    const std::vector<float> image = sampleImage(volume, plane);
    for (const float value : image) {
        QVERIFY2(std::abs(value - expected) < 1e-4,
                 qPrintable(QStringLiteral("got %1, want %2").arg(value).arg(expected)));
    }
}

void TestMprTools::roiOverUniformDisc() {
    // A cylinder along z of radius 12 mm holding 60 HU in -1000 HU air.
    const VolumeGeometry g = cube(64, {0.7, 0.7, 1.5});
    const glm::dvec3 axis = volumeCentre(g);
    const Volume volume = fill(g, [&](const glm::ivec3&, const glm::dvec3& p) {
        return glm::length(glm::dvec2(p - axis)) <= 12.0 ? 60.0 : -1000.0;
    });
    const SlicePlane plane = standardPlane(g, Orientation::Axial, axis, 100, 100);
    const RoiStatistics inside = ellipseStatistics(volume, plane, {axis, 8.0, 5.0}, 0.25);
    QCOMPARE(inside.mean, 60.0);
    QCOMPARE(inside.standardDeviation, 0.0);
    QCOMPARE(inside.minimum, 60.0);
    QCOMPARE(inside.maximum, 60.0);
    QVERIFY(std::abs(inside.areaMm2 - std::numbers::pi * 40.0) < 1e-9);
    QVERIFY(inside.samples > 1500);

    // Over the edge: the mean drops, the SD grows, min and max are the two materials.
    const RoiStatistics across = ellipseStatistics(volume, plane, {axis, 20.0, 20.0}, 0.25);
    QVERIFY(across.mean < 0.0);
    QVERIFY(across.standardDeviation > 100.0);
    QCOMPARE(across.minimum, -1000.0);
    QCOMPARE(across.maximum, 60.0);
}

void TestMprTools::roiOverRamp_data() {
    QTest::addColumn<double>("radiusU");
    QTest::addColumn<double>("radiusV");
    QTest::newRow("circle") << 10.0 << 10.0;
    QTest::newRow("wide") << 10.0 << 4.0;
    QTest::newRow("tall") << 4.0 << 10.0;
}

void TestMprTools::roiOverRamp() {
    QFETCH(double, radiusU);
    QFETCH(double, radiusV);
    // value = 3 x: over an ellipse with semi-axis a along x, the mean is the value at the
    // centre and the SD is 3 a / 2 (the variance of x over an ellipse is a^2 / 4).
    const VolumeGeometry g = cube(60, {0.9, 0.9, 1.0});
    const Volume volume = fill(g, [](const glm::ivec3&, const glm::dvec3& p) { return 3.0 * p.x; });
    const glm::dvec3 centre = volumeCentre(g) + glm::dvec3(1.3, -2.1, 0.4);
    const SlicePlane plane = standardPlane(g, Orientation::Axial, volumeCentre(g), 80, 80);
    const RoiStatistics stats = ellipseStatistics(volume, plane, {centre, radiusU, radiusV}, 0.05);
    QVERIFY2(std::abs(stats.mean - 3.0 * centre.x) < 1e-3, qPrintable(QString::number(stats.mean)));
    const double sd = 3.0 * radiusU / 2.0;
    QVERIFY2(std::abs(stats.standardDeviation - sd) < 0.01 * sd,
             qPrintable(QStringLiteral("SD %1, want %2").arg(stats.standardDeviation).arg(sd)));
    QVERIFY(std::abs(stats.areaMm2 - std::numbers::pi * radiusU * radiusV) < 1e-9);
}

void TestMprTools::roiEdgeCases() {
    const VolumeGeometry g = cube(16, {1.0, 1.0, 1.0});
    const Volume volume = fill(g, [](const glm::ivec3&, const glm::dvec3&) { return 5.0; });
    const SlicePlane plane = standardPlane(g, Orientation::Coronal, volumeCentre(g), 32, 32);
    const RoiStatistics none = ellipseStatistics(volume, plane, {volumeCentre(g), 0.0, 3.0});
    QCOMPARE(none.samples, std::size_t(0));
    QVERIFY(std::isnan(none.mean));
    QCOMPARE(none.areaMm2, 0.0);
    // Half outside the volume: only the samples inside count.
    const glm::dvec3 corner = g.toPatient({0, 8, 0});
    const RoiStatistics half = ellipseStatistics(volume, plane, {corner, 6.0, 6.0}, 0.5);
    QCOMPARE(half.mean, 5.0);
    QVERIFY(half.samples > 0);
    const RoiStatistics full = ellipseStatistics(volume, plane, {volumeCentre(g), 6.0, 6.0}, 0.5);
    QVERIFY(half.samples < full.samples);
}

QTEST_APPLESS_MAIN(TestMprTools)

#include "test_mpr_tools.moc"
