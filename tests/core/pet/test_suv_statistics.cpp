// SUVmax, SUVmean and SUVpeak (core/pet/SuvStatistics.h) on synthetic volumes whose
// answers are counted by hand: a uniform sphere in a background, a single hot voxel with
// isotropic and anisotropic voxels.
#include <QTest>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <tuple>
#include <vector>

#include "core/pet/SuvStatistics.h"

using namespace lucent;

namespace {

Volume uniform(const glm::ivec3& dims, const glm::dvec3& spacing, float value) {
    VolumeGeometry g;
    g.dims = dims;
    g.spacing = spacing;
    g.origin = glm::dvec3(-10.0, 5.0, 100.0);
    Volume v(g, VoxelType::Float32);
    for (float& x : v.voxels<float>()) {
        x = value;
    }
    return v;
}

using VoxelSet = std::set<std::tuple<int, int, int>>;

VoxelSet toSet(const std::vector<glm::ivec3>& voxels) {
    VoxelSet out;
    for (const glm::ivec3& v : voxels) {
        out.emplace(v.x, v.y, v.z);
    }
    return out;
}

void set(Volume& v, const glm::ivec3& ijk, float value) {
    v.voxels<float>()[v.linearIndex(ijk.x, ijk.y, ijk.z)] = value;
}

} // namespace

class TestSuvStatistics : public QObject {
    Q_OBJECT
private slots:
    void peakSphereIsOneMillilitre() {
        const double r = suvPeakRadiusMm();
        QVERIFY(std::abs(4.0 / 3.0 * std::numbers::pi * r * r * r - 1000.0) < 1e-9);
        QVERIFY(std::abs(r - 6.2035) < 1e-4);
    }

    // A sphere of 5 (radius 12 mm, 7.2 mL) in a background of 1, 1 mm voxels: every
    // statistic over the sphere is 5, as the 1 mL sphere around its centre lies inside it.
    void uniformSphere() {
        Volume v = uniform(glm::ivec3(41), glm::dvec3(1.0), 1.0f);
        const glm::dvec3 centre = v.geometry().toPatient(glm::dvec3(20.0));
        const std::vector<glm::ivec3> sphere =
            ellipsoidVoxels(v.geometry(), centre, glm::dvec3(12.0));
        for (const glm::ivec3& ijk : sphere) {
            set(v, ijk, 5.0f);
        }
        const SuvStatistics s = suvStatistics(v, sphere);
        QCOMPARE(s.voxels, sphere.size());
        QCOMPARE(s.max, 5.0);
        QCOMPARE(s.mean, 5.0);
        QCOMPARE(s.peak, 5.0);
        // A 1 mm radius ball of 1 mm voxels: the centre and its 6 face neighbours.
        QCOMPARE(ellipsoidVoxels(v.geometry(), centre, glm::dvec3(1.0)).size(), std::size_t(7));
    }

    // One voxel of 10 in a background of 1, 2 mm voxels. The 1 mL sphere (r 6.2035 mm)
    // holds the offsets with i^2 + j^2 + k^2 <= 9: shells 0, 1, 2, 3, 4, 5, 6, 8, 9 hold
    // 1 + 6 + 12 + 8 + 6 + 24 + 24 + 12 + 30 = 123 voxels, so SUVpeak = (10 + 122) / 123.
    void singleHotVoxel() {
        Volume v = uniform(glm::ivec3(21), glm::dvec3(2.0), 1.0f);
        const glm::ivec3 hot(10, 10, 10);
        set(v, hot, 10.0f);
        const std::vector<glm::ivec3> region = {hot, {3, 3, 3}, {10, 10, 11}};
        const SuvStatistics s = suvStatistics(v, region);
        QCOMPARE(s.max, 10.0);
        QCOMPARE(s.maxVoxel, hot);
        QCOMPARE(s.mean, 12.0 / 3.0);
        QVERIFY(std::abs(s.peak - 132.0 / 123.0) < 1e-12);
        QCOMPARE(s.peakVoxel, hot);
        QVERIFY(std::abs(sphereMean(v, hot, suvPeakRadiusMm()) - 132.0 / 123.0) < 1e-12);
    }

    // 2 x 2 x 4 mm voxels: i^2 + j^2 + 4 k^2 <= 9.62. k = 0 holds 29 voxels (1 + 2*5 + 2*5
    // + 2*1 over i = 0, +-1, +-2, +-3), k = +-1 hold 21 each (i^2 + j^2 <= 5), k = +-2 none:
    // 71 voxels, SUVpeak = (10 + 70) / 71.
    void anisotropicVoxels() {
        Volume v = uniform(glm::ivec3(15, 15, 9), glm::dvec3(2.0, 2.0, 4.0), 1.0f);
        const glm::ivec3 hot(7, 7, 4);
        set(v, hot, 10.0f);
        const std::vector<glm::ivec3> region = {hot};
        QVERIFY(std::abs(suvStatistics(v, region).peak - 80.0 / 71.0) < 1e-12);
    }

    // At the volume's edge the sphere holds only the voxels inside the volume.
    void edgesAndEmptyRegions() {
        Volume v = uniform(glm::ivec3(8), glm::dvec3(10.0), 2.0f);
        set(v, glm::ivec3(0), 8.0f);
        // 10 mm voxels: the sphere is the centre voxel alone.
        QCOMPARE(sphereMean(v, glm::ivec3(0), suvPeakRadiusMm()), 8.0);
        QVERIFY(std::isnan(sphereMean(v, glm::ivec3(-1, 0, 0), suvPeakRadiusMm())));
        const SuvStatistics none = suvStatistics(v, {});
        QCOMPARE(none.voxels, std::size_t(0));
        QVERIFY(std::isnan(none.max) && std::isnan(none.mean) && std::isnan(none.peak));
        const std::vector<glm::ivec3> outside = {{9, 0, 0}, {0, 0, 0}};
        QCOMPARE(suvStatistics(v, outside).voxels, std::size_t(1));
        // 2 mm voxels: the corner's sphere is the octant i, j, k >= 0 of the 123 offsets
        // (1 + 3 + 3 + 1 + 3 + 6 + 3 + 3 + 6 = 29 voxels: shells 0 ... 9 without signs).
        Volume w = uniform(glm::ivec3(8), glm::dvec3(2.0), 1.0f);
        set(w, glm::ivec3(0), 27.0f);
        QVERIFY(std::abs(sphereMean(w, glm::ivec3(0), suvPeakRadiusMm()) - 55.0 / 29.0) < 1e-12);
    }

    // An ellipsoid turned 45 degrees about k in 1 mm voxels: semi-axes 3.2 mm along
    // (1, 1, 0)/sqrt2, 1.1 mm along (-1, 1, 0)/sqrt2 and 1.1 mm along k. A voxel offset
    // (i, j, k) is inside when (i + j)^2 / 20.48 + (j - i)^2 / 2.42 + k^2 / 1.21 <= 1:
    // k = 0 holds the centre, (+-1, +-1) and (+-2, +-2) along the long axis, the 4 face
    // neighbours (0.46) and (2, 1), (1, 2), (-2, -1), (-1, -2) (0.85); k = +-1 the centre only.
    void orientedEllipsoid() {
        const Volume v = uniform(glm::ivec3(21), glm::dvec3(1.0), 1.0f);
        const glm::dvec3 centre = v.geometry().toPatient(glm::dvec3(10.0));
        const double h = std::sqrt(0.5);
        const glm::dmat3 axes(glm::dvec3(h, h, 0.0), glm::dvec3(-h, h, 0.0), glm::dvec3(0, 0, 1));
        const std::vector<glm::ivec3> voxels =
            ellipsoidVoxels(v.geometry(), centre, axes, glm::dvec3(3.2, 1.1, 1.1));
        QCOMPARE(voxels.size(), std::size_t(5 + 4 + 4 + 2));
        for (const glm::ivec3 offset :
             {glm::ivec3(2, 2, 0), glm::ivec3(-2, -2, 0), glm::ivec3(1, 0, 0), glm::ivec3(2, 1, 0),
              glm::ivec3(0, 0, 1)}) {
            QVERIFY(std::count(voxels.begin(), voxels.end(), glm::ivec3(10) + offset) == 1);
        }
        QVERIFY(std::count(voxels.begin(), voxels.end(), glm::ivec3(12, 8, 10)) == 0); // short axis
        // Along the volume's axes it is the axis-aligned ellipsoid.
        QCOMPARE(ellipsoidVoxels(v.geometry(), centre, glm::dmat3(1.0), glm::dvec3(3.0, 1.0, 2.0)),
                 ellipsoidVoxels(v.geometry(), centre, glm::dvec3(3.0, 1.0, 2.0)));
    }

    // An ellipse on a coronal plane (u = L, v = I) of 2 mm voxels, semi-axes 5 mm along L and
    // 3 mm along I: the ellipsoid reaches 3 mm (the shorter) along the normal (P), and is
    // centred on the plane even when the ellipse's centre lies off it.
    void ellipseRegionSpansAnEllipsoid() {
        const Volume v = uniform(glm::ivec3(15), glm::dvec3(2.0), 1.0f);
        SlicePlane plane;
        plane.centre = v.geometry().toPatient(glm::dvec3(7.0));
        plane.u = glm::dvec3(1, 0, 0);
        plane.v = glm::dvec3(0, 0, -1);
        const EllipseRoi ellipse{plane.centre + glm::dvec3(0.0, 0.7, 0.0), 5.0, 3.0};
        const std::vector<glm::ivec3> region = ellipseSuvRegion(v.geometry(), plane, ellipse);
        const std::vector<glm::ivec3> expected =
            ellipsoidVoxels(v.geometry(), plane.centre, glm::dvec3(5.0, 3.0, 3.0));
        QVERIFY(toSet(region) == toSet(expected));
        // Offsets (i, j, k) in voxels: i^2 / 6.25 + (j^2 + k^2) / 2.25 <= 1: 5 voxels at
        // j = k = 0 (|i| <= 2), and (0, +-1, 0), (0, 0, +-1), (+-1, +-1, 0), (+-1, 0, +-1),
        // (0, +-1, +-1).
        QCOMPARE(region.size(), std::size_t(5 + 4 + 8 + 4));
    }

    void suvVolumeScales() {
        VolumeGeometry g;
        g.dims = glm::ivec3(2, 1, 1);
        Volume activity(g, VoxelType::Int16);
        activity.voxels<std::int16_t>()[0] = 1000;
        activity.voxels<std::int16_t>()[1] = -3;
        activity.modality = "PT";
        const Volume suv = suvVolume(activity, 0.004);
        QCOMPARE(suv.type(), VoxelType::Float32);
        QCOMPARE(suv.modality, std::string("PT"));
        QCOMPARE(suv.value(0, 0, 0), double(4.0f));
        QCOMPARE(suv.value(1, 0, 0), double(-0.012f));
    }
};

QTEST_GUILESS_MAIN(TestSuvStatistics)
#include "test_suv_statistics.moc"
