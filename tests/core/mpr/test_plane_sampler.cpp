// The MPR plane sampler: trilinear sampling reproduces linear fields exactly for
// any volume direction, the radiological display conventions, slabs, and fill.
#include <QTest>

#include <cmath>
#include <cstdint>

#include <glm/gtc/matrix_transform.hpp>

#include "core/mpr/PlaneSampler.h"

using namespace lucent;

Q_DECLARE_METATYPE(lucent::VolumeGeometry)

namespace {

// value = dot(gradient, LPS position) + offset
struct LinearField {
    glm::dvec3 gradient{0.0};
    double offset = 0.0;
    double operator()(const glm::dvec3& p) const { return glm::dot(gradient, p) + offset; }
};

Volume makeVolume(const VolumeGeometry& g, const LinearField& field) {
    Volume volume(g, VoxelType::Float32);
    auto voxels = volume.voxels<float>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                voxels[volume.linearIndex(i, j, k)] =
                    static_cast<float>(field(g.toPatient(glm::dvec3(i, j, k))));
            }
        }
    }
    return volume;
}

VolumeGeometry geometry(const glm::dmat3& direction) {
    VolumeGeometry g;
    g.dims = {21, 17, 13};
    g.spacing = {0.8, 1.1, 2.5};
    g.origin = {-12.0, 30.5, -101.0};
    g.direction = direction;
    return g;
}

glm::dmat3 rotation(double degrees, const glm::dvec3& axis) {
    return glm::dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(degrees), glm::normalize(axis)));
}

// Strictly inside the voxel-centre box, where trilinear interpolation is exact for a linear field.
bool inside(const VolumeGeometry& g, const glm::dvec3& p) {
    const glm::dvec3 ijk = g.toIndex(p);
    for (int a = 0; a < 3; ++a) {
        if (ijk[a] < 1e-6 || ijk[a] > g.dims[a] - 1 - 1e-6) {
            return false;
        }
    }
    return true;
}

// Compares every pixel inside the volume with the field; returns how many were inside.
int checkPlane(const Volume& volume, const SlicePlane& plane, const LinearField& field) {
    const std::vector<float> image = sampleImage(volume, plane);
    if (image.size() != static_cast<std::size_t>(plane.width) * plane.height) {
        qWarning("image has the wrong size");
        return -1;
    }
    int count = 0;
    for (int y = 0; y < plane.height; ++y) {
        for (int x = 0; x < plane.width; ++x) {
            const glm::dvec3 p = plane.pointAt(x, y);
            if (!inside(volume.geometry(), p)) {
                continue;
            }
            const float got = image[static_cast<std::size_t>(y) * plane.width + x];
            const double want = field(p);
            if (!(std::abs(got - want) <= 2e-4 + 1e-6 * std::abs(want))) {
                qWarning("pixel (%d, %d): got %f, want %f", x, y, got, want);
                return -1;
            }
            ++count;
        }
    }
    return count;
}

const LinearField kField{{1.5, -2.25, 0.75}, 40.0};

} // namespace

class TestPlaneSampler : public QObject {
    Q_OBJECT

private slots:
    void linearField_data();
    void linearField();
    void displayConventions();
    void slab_data();
    void slab();
    void outsideIsFill();
    void integerVoxels();
    void sliceStepAndHelpers();
    void defaultWindows();
};

void TestPlaneSampler::linearField_data() {
    QTest::addColumn<VolumeGeometry>("geometry");
    QTest::newRow("identity") << geometry(glm::dmat3(1.0));
    QTest::newRow("flipped") << geometry(glm::dmat3({-1, 0, 0}, {0, 1, 0}, {0, 0, -1}));
    QTest::newRow("swapped axes") << geometry(glm::dmat3({0, 0, 1}, {1, 0, 0}, {0, -1, 0}));
    QTest::newRow("oblique") << geometry(rotation(27.0, {0.3, -1.0, 0.6}));
    QTest::newRow("oblique flipped") << geometry(rotation(-41.0, {1.0, 0.2, -0.4}) *
                                                 glm::dmat3({1, 0, 0}, {0, -1, 0}, {0, 0, 1}));
    // Gantry tilt: the slice axis is not perpendicular to the rows and columns.
    QTest::newRow("sheared") << geometry(
        glm::dmat3({1, 0, 0}, {0, 1, 0}, glm::normalize(glm::dvec3(0, 0.3, 1))));
}

void TestPlaneSampler::linearField() {
    QFETCH(VolumeGeometry, geometry);
    const Volume volume = makeVolume(geometry, kField);
    const glm::dvec3 centre = volumeCentre(geometry) + glm::dvec3(0.37, -0.61, 0.23);
    for (const Orientation o : {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
        const SlicePlane plane = standardPlane(geometry, o, centre, 61, 47);
        QVERIFY2(checkPlane(volume, plane, kField) > 100, orientationName(o));
    }
    // An oblique plane with an odd pixel size, through an off-centre point.
    SlicePlane oblique;
    oblique.u = glm::normalize(glm::dvec3(0.8, 0.3, -0.2));
    oblique.v = glm::normalize(glm::cross(glm::dvec3(0.1, 0.4, 0.9), oblique.u));
    oblique.centre = centre + glm::dvec3(1.3, 0.0, -0.9);
    oblique.pixelSize = 0.537;
    oblique.width = 53;
    oblique.height = 41;
    QVERIFY(checkPlane(volume, oblique, kField) > 100);
}

void TestPlaneSampler::displayConventions() {
    const VolumeGeometry g =
        geometry(rotation(180.0, {0, 0, 1})); // i runs to patient right, j to the front
    const glm::dvec3 c = volumeCentre(g);
    auto pixel = [](const std::vector<float>& image, const SlicePlane& p, int x, int y) {
        return image[static_cast<std::size_t>(y) * p.width + x];
    };

    // Axial, seen from the feet: right is patient Left (+x), down is Posterior (+y).
    const SlicePlane axial = standardPlane(g, Orientation::Axial, c, 9, 9);
    QVERIFY(axial.pointAt(5, 4).x > axial.pointAt(4, 4).x);
    QVERIFY(axial.pointAt(4, 5).y > axial.pointAt(4, 4).y);
    QCOMPARE(axial.normal().z, 1.0);
    const std::vector<float> ax = sampleImage(makeVolume(g, {{1, 0, 0}, 0}), axial);
    QVERIFY(pixel(ax, axial, 5, 4) > pixel(ax, axial, 4, 4));

    // Coronal, seen from the front: right is +x, down is Inferior (-z).
    const SlicePlane coronal = standardPlane(g, Orientation::Coronal, c, 9, 9);
    QVERIFY(coronal.pointAt(5, 4).x > coronal.pointAt(4, 4).x);
    QVERIFY(coronal.pointAt(4, 5).z < coronal.pointAt(4, 4).z);
    const std::vector<float> co = sampleImage(makeVolume(g, {{0, 0, 1}, 0}), coronal);
    QVERIFY(pixel(co, coronal, 4, 5) < pixel(co, coronal, 4, 4));

    // Sagittal, seen from the patient's left: right is Posterior (+y), down is -z.
    const SlicePlane sagittal = standardPlane(g, Orientation::Sagittal, c, 9, 9);
    QVERIFY(sagittal.pointAt(5, 4).y > sagittal.pointAt(4, 4).y);
    QVERIFY(sagittal.pointAt(4, 5).z < sagittal.pointAt(4, 4).z);
    const std::vector<float> sa = sampleImage(makeVolume(g, {{0, 1, 0}, 0}), sagittal);
    QVERIFY(pixel(sa, sagittal, 5, 4) > pixel(sa, sagittal, 4, 4));

    // The labels at the edges: left, right, top, bottom.
    QCOMPARE(directionLabel(-axial.u), std::string("R"));
    QCOMPARE(directionLabel(axial.u), std::string("L"));
    QCOMPARE(directionLabel(-axial.v), std::string("A"));
    QCOMPARE(directionLabel(coronal.v), std::string("I"));
    QCOMPARE(directionLabel(-sagittal.u), std::string("A"));
    QCOMPARE(directionLabel(-sagittal.v), std::string("S"));

    // The pixel size fits the volume: the image centre maps back to the centre.
    const glm::dvec2 mid = axial.pixelOf(c);
    QCOMPARE(mid.x, 4.0);
    QCOMPARE(mid.y, 4.0);
}

void TestPlaneSampler::slab_data() {
    QTest::addColumn<VolumeGeometry>("geometry");
    QTest::newRow("identity") << geometry(glm::dmat3(1.0));
    QTest::newRow("oblique flipped")
        << geometry(rotation(33.0, {0.2, 1.0, 0.1}) * glm::dmat3({-1, 0, 0}, {0, 1, 0}, {0, 0, 1}));
}

void TestPlaneSampler::slab() {
    QFETCH(VolumeGeometry, geometry);
    // The field grows along +z: across an axial slab of thickness t the largest value
    // is half a slab up, the smallest half a slab down, and the mean the middle one.
    const LinearField field{{0.0, 0.0, 3.0}, -7.0};
    const Volume volume = makeVolume(geometry, field);
    const glm::dvec3 c = volumeCentre(geometry);
    SlicePlane plane = standardPlane(geometry, Orientation::Axial, c, 5, 5);
    plane.pixelSize = 0.5; // stay well inside the volume
    plane.slabThickness = 4.2;
    const double mid = field(c);
    const double half = 3.0 * 0.5 * plane.slabThickness;

    for (const auto& [mode, want] :
         {std::pair{SlabMode::Mip, mid + half}, std::pair{SlabMode::MinIp, mid - half},
          std::pair{SlabMode::Average, mid}}) {
        plane.slabMode = mode;
        const std::vector<float> image = sampleImage(volume, plane);
        const float centrePixel = image[2 * 5 + 2];
        QVERIFY2(std::abs(centrePixel - want) < 1e-3, qPrintable(QString("mode %1: got %2, want %3")
                                                                     .arg(static_cast<int>(mode))
                                                                     .arg(centrePixel)
                                                                     .arg(want)));
    }
}

void TestPlaneSampler::outsideIsFill() {
    const VolumeGeometry g = geometry(rotation(20.0, {1, 1, 0}));
    const Volume volume = makeVolume(g, kField);
    SlicePlane far =
        standardPlane(g, Orientation::Axial, volumeCentre(g) + glm::dvec3(0, 0, 500), 8, 8);
    for (const float v : sampleImage(volume, far)) {
        QVERIFY(std::isnan(v));
    }
    for (const float v : sampleImage(volume, far, -2048.0f)) {
        QCOMPARE(v, -2048.0f);
    }
    far.slabThickness = 10.0;
    for (const float v : sampleImage(volume, far, -5.0f)) {
        QCOMPARE(v, -5.0f);
    }
    // A wide plane through the centre: the middle is inside, the corners are outside.
    SlicePlane wide = standardPlane(g, Orientation::Coronal, volumeCentre(g), 101, 101);
    wide.pixelSize = 2.0;
    const std::vector<float> image = sampleImage(volume, wide, -1.0f);
    QCOMPARE(image.front(), -1.0f);
    QCOMPARE(image.back(), -1.0f);
    QVERIFY(image[50 * 101 + 50] != -1.0f);
    QVERIFY(std::isnan(sampleAt(volume, glm::dvec3(-0.51, 0, 0))));
    QCOMPARE(sampleAt(volume, glm::dvec3(-0.49, 0, 0)), volume.value(0, 0, 0));
    QCOMPARE(sampleAt(volume, glm::dvec3(0, g.dims.y, 0), 7.0), 7.0);
}

void TestPlaneSampler::integerVoxels() {
    VolumeGeometry g = geometry(glm::dmat3({0, 1, 0}, {-1, 0, 0}, {0, 0, 1}));
    Volume volume(g, VoxelType::Int16);
    auto voxels = volume.voxels<std::int16_t>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                voxels[volume.linearIndex(i, j, k)] =
                    static_cast<std::int16_t>(-1000 + 3 * i + 5 * j - 7 * k);
            }
        }
    }
    QCOMPARE(sampleAt(volume, {2.5, 3.25, 4.0}), -1000 + 7.5 + 16.25 - 28.0);
    QCOMPARE(sampleAt(volume, {0.0, 0.0, 0.0}), -1000.0);
    QCOMPARE(sampleAt(volume, {g.dims.x - 1.0, g.dims.y - 1.0, g.dims.z - 1.0}),
             volume.value(g.dims.x - 1, g.dims.y - 1, g.dims.z - 1));
}

void TestPlaneSampler::sliceStepAndHelpers() {
    const VolumeGeometry g = geometry(glm::dmat3({-1, 0, 0}, {0, 1, 0}, {0, 0, -1}));
    QCOMPARE(sliceStep(g, {0, 0, 1}), 2.5);
    QCOMPARE(sliceStep(g, {0, -1, 0}), 1.1);
    QCOMPARE(sliceStep(g, {1, 0, 0}), 0.8);
    // 45 degrees between i and j: the step that moves one full voxel along either.
    QVERIFY(std::abs(sliceStep(g, {1, 1, 0}) - 0.8 * std::sqrt(2.0)) < 1e-12);

    QCOMPARE(windowToGrey(40.0, 40.0, 400.0), std::uint8_t(128));
    QCOMPARE(windowToGrey(-160.0, 40.0, 400.0), std::uint8_t(0));
    QCOMPARE(windowToGrey(240.0, 40.0, 400.0), std::uint8_t(255));
    QCOMPARE(windowToGrey(-3000.0, 40.0, 400.0), std::uint8_t(0));
    QCOMPARE(windowToGrey(3000.0, 40.0, 400.0), std::uint8_t(255));
    QCOMPARE(windowToGrey(std::nan(""), 40.0, 400.0), std::uint8_t(0));
    QCOMPARE(windowToGrey(10.0, 10.0, 0.0), std::uint8_t(128));

    QCOMPARE(directionLabel({0, 0, -1}), std::string("I"));
    QCOMPARE(directionLabel({0.1, -0.7, 0.7}), std::string("AS"));
    QCOMPARE(directionLabel({-0.9, 0.1, 0.3}), std::string("RS"));
    QCOMPARE(directionLabel({0, 0, 0}), std::string());
}

void TestPlaneSampler::defaultWindows() {
    VolumeGeometry g;
    g.dims = {10, 10, 10};
    Volume volume(g, VoxelType::UInt16);
    auto voxels = volume.voxels<std::uint16_t>();
    for (std::size_t n = 0; n < voxels.size(); ++n) {
        voxels[n] = static_cast<std::uint16_t>(n); // 0 .. 999
    }
    const WindowLevel mr = defaultWindow(volume);
    // The 1st and 99th percentiles: 9 and 989.
    QCOMPARE(mr.center, 499.0);
    QCOMPARE(mr.width, 980.0);
    QCOMPARE(mr.step, 0.98);
    volume.modality = "CT";
    const WindowLevel ct = defaultWindow(volume);
    QCOMPARE(ct.center, 40.0);
    QCOMPARE(ct.width, 400.0);
    QCOMPARE(ct.step, 1.0);
}

QTEST_APPLESS_MAIN(TestPlaneSampler)
#include "test_plane_sampler.moc"
