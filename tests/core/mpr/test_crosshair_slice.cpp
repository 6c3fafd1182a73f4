// The linked MPR view's plane through the crosshair (core/mpr/CrosshairSlice):
// it passes through the crosshair, is centred on the volume in plane, keeps the
// unturned fit when turned, zooms about its centre and pans along u and v; the
// windowed grey image is windowToGrey of each sample; a crosshair outside the
// volume is brought into the box of its voxel centres, also for a turned volume.
#include <QTest>

#include <glm/gtc/matrix_transform.hpp>

#include "core/mpr/CrosshairSlice.h"

using namespace lucent;

namespace {

VolumeGeometry turnedGeometry() {
    VolumeGeometry g;
    g.dims = {40, 30, 20};
    g.spacing = {0.8, 0.9, 2.5};
    g.origin = {-10.0, 25.0, 100.0};
    g.direction = glm::dmat3(glm::rotate(glm::dmat4(1.0), 0.3, glm::dvec3(0.2, 1.0, 0.4)));
    return g;
}

} // namespace

class TestCrosshairSlice : public QObject {
    Q_OBJECT

private slots:
    void planeGoesThroughTheCrosshair() {
        const VolumeGeometry g = turnedGeometry();
        const glm::dvec3 mid = volumeCentre(g);
        const glm::dvec3 crosshair = mid + glm::dvec3(3.0, -4.0, 7.5);
        for (const Orientation o :
             {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
            const SlicePlane fitted = standardPlane(g, o, mid, 200, 150);
            const SlicePlane p = crosshairPlane(g, o, crosshair, 200, 150);
            QVERIFY(std::abs(p.distance(crosshair)) < 1e-9);
            // In plane it is centred on the volume's centre.
            QVERIFY(std::abs(glm::dot(p.centre - mid, p.u)) < 1e-9);
            QVERIFY(std::abs(glm::dot(p.centre - mid, p.v)) < 1e-9);
            QCOMPARE(p.pixelSize, fitted.pixelSize);
            QCOMPARE(p.width, 200);
            QCOMPARE(p.height, 150);

            // Turned, zoomed and panned: the fit of the unturned plane over the zoom.
            const glm::dmat3 turn(glm::rotate(glm::dmat4(1.0), 0.4, fitted.normal()));
            const SlicePlane q =
                crosshairPlane(g, o, crosshair, 200, 150, turn, 2.0, glm::dvec2(5.0, -3.0));
            QCOMPARE(q.pixelSize, fitted.pixelSize / 2.0);
            QVERIFY(glm::length(q.u - turn * fitted.u) < 1e-12);
            QVERIFY(std::abs(q.distance(crosshair)) < 1e-9);
            QVERIFY(std::abs(glm::dot(q.centre - mid, q.u) - 5.0) < 1e-9);
            QVERIFY(std::abs(glm::dot(q.centre - mid, q.v) + 3.0) < 1e-9);
        }
        // No voxels: centred on the crosshair.
        const SlicePlane none =
            crosshairPlane(VolumeGeometry{}, Orientation::Axial, glm::dvec3(1.0, 2.0, 3.0), 10, 10);
        QVERIFY(glm::length(none.centre - glm::dvec3(1.0, 2.0, 3.0)) < 1e-12);
    }

    void windowedGreyIsWindowToGreyOfEachSample() {
        const std::vector<float> samples{
            -1000.0f, -160.0f, 40.0f, 239.0f, 3000.0f, std::numeric_limits<float>::quiet_NaN()};
        const std::vector<std::uint8_t> grey = windowedGrey(samples, 40.0, 400.0);
        QCOMPARE(grey.size(), samples.size());
        for (std::size_t i = 0; i < samples.size(); ++i) {
            QCOMPARE(grey[i], windowToGrey(samples[i], 40.0, 400.0));
        }
        QCOMPARE(grey.front(), std::uint8_t(0));
        QCOMPARE(grey[4], std::uint8_t(255));
    }

    void crosshairIsBroughtIntoTheVolume() {
        const VolumeGeometry g = turnedGeometry();
        const glm::dvec3 inside = g.toPatient(glm::dvec3(3.0, 4.5, 19.0));
        QCOMPARE(clampToVolume(g, inside), inside);
        const glm::dvec3 outside = g.toPatient(glm::dvec3(-5.0, 12.0, 60.0));
        const glm::dvec3 clamped = clampToVolume(g, outside);
        const glm::dvec3 ijk = glm::dvec3(g.patientToIndex() * glm::dvec4(clamped, 1.0));
        QVERIFY(glm::length(ijk - glm::dvec3(0.0, 12.0, 19.0)) < 1e-9);
        QCOMPARE(clampToVolume(VolumeGeometry{}, outside), outside);
    }
};

QTEST_APPLESS_MAIN(TestCrosshairSlice)
#include "test_crosshair_slice.moc"
