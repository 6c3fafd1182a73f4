// The isosurface extractor on synthetic volumes: closed manifold meshes on
// noise (the hardest case for a table), O(h²) accuracy on a sphere, frames
// that mirror, objects cut by the field of view or the clip box, the same mesh
// for any thread count and voxel type, and its errors and cancellation.
#include <QTest>

#include <omp.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/surface/GaussianBlur.h"
#include "core/surface/IsosurfaceExtractor.h"
#include "core/surface/MeshChecks.h"
#include "tests/core/surface/IsoVolumes.h"

using namespace lucent;
using namespace lucent::test;

namespace {

// Closed, manifold, consistently oriented, no zero-area triangle, positive volume.
void verifyClosed(const TriangleMesh& mesh, const char* what) {
    const MeshReport r = checkMesh(mesh);
    const QString s = QString("%1: %2 triangles, %3 boundary edges, %4 non-manifold edges, %5 "
                              "non-manifold vertices, %6 repeated directed edges, %7 zero-area, "
                              "%8 unused vertices, volume %9")
                          .arg(what)
                          .arg(r.triangles)
                          .arg(r.boundaryEdges)
                          .arg(r.nonManifoldEdges)
                          .arg(r.nonManifoldVertices)
                          .arg(r.repeatedDirectedEdges)
                          .arg(r.zeroAreaTriangles)
                          .arg(r.unusedVertices)
                          .arg(r.volume);
    QVERIFY2(r.triangles > 0, qPrintable(s));
    QVERIFY2(r.closedManifold(), qPrintable(s));
    QVERIFY2(r.zeroAreaTriangles == 0 && r.unusedVertices == 0, qPrintable(s));
    QVERIFY2(r.volume > 0.0, qPrintable(s));
    // Every closed component bounds a volume: V - E + F is even.
    QVERIFY2(r.euler % 2 == 0, qPrintable(s));
}

Volume mirrored(const Volume& v) {
    Volume out(v.geometry(), v.type());
    std::copy(v.bytes().begin(), v.bytes().end(), out.bytes().begin());
    VolumeGeometry g = v.geometry();
    // A rotation (det +1) with one axis reversed: det -1.
    g.direction = glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 0, -1));
    out.setGeometry(g);
    return out;
}

} // namespace

class TestIsosurfaceExtractor : public QObject {
    Q_OBJECT

private slots:
    void gaussianNoiseIsClosed_data() {
        QTest::addColumn<unsigned>("seed");
        QTest::newRow("seed 1") << 1u;
        QTest::newRow("seed 2") << 2u;
        QTest::newRow("seed 3") << 3u;
    }
    void gaussianNoiseIsClosed() {
        QFETCH(unsigned, seed);
        const Volume v = gaussianNoise(40, seed);
        const TriangleMesh mesh = contour(v, 0.0).mesh;
        verifyClosed(mesh, "gaussian noise");
        const auto [triangles, vertices] = bruteForceCounts(v, 0.0);
        QCOMPARE(mesh.triangles.size(), triangles);
        QCOMPARE(mesh.vertices.size(), vertices);
    }

    void binaryNoiseIsClosed() {
        const IsosurfaceResult r = contour(integerNoise(40, 0, 1, 7), 0.5);
        verifyClosed(r.mesh, "50 % binary");
        QCOMPARE(r.warnings.size(), std::size_t(1));
    }

    // Voxels equal to the iso value everywhere: ties must not give zero areas.
    void integerNoiseWithTiesIsClosed() {
        verifyClosed(contour(integerNoise(40, -2, 2, 11), 0.0).mesh, "integer noise at 0");
        verifyClosed(contour(integerNoise(40, -2, 2, 12), 2.0).mesh, "integer noise at its max");
    }

    void sphereConvergesAsHSquared() {
        const double a = 10.0;
        double areaError[2], volumeError[2];
        const double h[2] = {1.0, 0.5};
        for (int i = 0; i < 2; ++i) {
            const IsosurfaceResult r = contour(sphereDistance(a, h[i]), 0.0);
            verifyClosed(r.mesh, "sphere");
            const MeshReport m = checkMesh(r.mesh);
            QCOMPARE(m.components, std::size_t(1));
            QCOMPARE(m.euler, 2LL);
            areaError[i] = std::abs(m.area / sphereArea(a) - 1.0);
            volumeError[i] = std::abs(m.volume / sphereVolume(a) - 1.0);
            qInfo("h = %.2f: %zu triangles, area error %.2e, volume error %.2e, hmax %.3f", h[i],
                  m.triangles, areaError[i], volumeError[i], m.hMax);
        }
        QVERIFY(areaError[0] < 4e-3);
        QVERIFY(volumeError[0] < 7e-3);
        QVERIFY(areaError[1] < 1e-3);
        QVERIFY(volumeError[1] < 2e-3);
        QVERIFY(areaError[0] / areaError[1] > 3.0);
        QVERIFY(volumeError[0] / volumeError[1] > 3.0);
    }

    void anisotropicSpacingKeepsTheSphere() {
        const double a = 10.0;
        VolumeGeometry g = cubeAround(glm::dvec3(0.0), 48, 0.5);
        g.dims.z = 28;
        g.spacing.z = 0.9;
        g.origin.z = -0.5 * 0.9 * 27;
        const Volume v = sampledVolume(g, VoxelType::Float32, [a](const glm::dvec3& x) {
            return a - glm::length(x - kSphereCentre);
        });
        const MeshReport m = checkMesh(contour(v, 0.0).mesh);
        QVERIFY(m.closedManifold());
        QVERIFY(std::abs(m.volume / sphereVolume(a) - 1.0) < 5e-3);
    }

    // A mirrored frame: same surface, same positive volume, normals still out.
    void mirroredFrameKeepsVolumePositive() {
        const Volume v = sphereDistance(10.0, 1.0);
        const MeshReport plain = checkMesh(contour(v, 0.0).mesh);
        const Volume m = mirrored(v);
        QVERIFY(glm::determinant(glm::dmat3(m.geometry().indexToPatient())) < 0.0);
        const TriangleMesh mesh = contour(m, 0.0).mesh;
        verifyClosed(mesh, "mirrored sphere");
        const MeshReport r = checkMesh(mesh);
        QVERIFY(std::abs(r.volume - plain.volume) < 1e-9 * plain.volume);
        QVERIFY(std::abs(r.area - plain.area) < 1e-9 * plain.area);
        verifyClosed(contour(mirrored(gaussianNoise(30, 5)), 0.0).mesh, "mirrored noise");
    }

    // A ball centred on a corner of the volume: only its octant is inside the
    // field of view, closed by caps about half a voxel beyond the border voxels.
    // The same ball in a larger volume, clipped to the first one's box, gives
    // the very same mesh.
    void objectCutByTheFieldOfViewIsClosed() {
        const double a = 8.0;
        const auto ball = [a](const glm::dvec3& x) { return a - glm::length(x); };
        VolumeGeometry g;
        g.dims = glm::ivec3(20);
        const TriangleMesh mesh = contour(sampledVolume(g, VoxelType::Float32, ball), 0.0).mesh;
        verifyClosed(mesh, "cut ball");
        const double octant = sphereVolume(a) / 8.0;
        const double grown = octant + 3.0 * 0.5 * std::numbers::pi * a * a / 4.0 + 0.75 * a + 0.125;
        const double volume = checkMesh(mesh).volume;
        QVERIFY2(volume > octant && volume < grown, qPrintable(QString::number(volume)));

        VolumeGeometry large = g;
        large.dims = glm::ivec3(40);
        large.origin = glm::dvec3(-20.0);
        IsosurfaceOptions o;
        o.clip.lo = glm::dvec3(20.0);
        const TriangleMesh clipped =
            extractIsosurface(sampledVolume(large, VoxelType::Float32, ball), o).mesh;
        QVERIFY(clipped.triangles == mesh.triangles);
        QVERIFY(clipped.vertices == mesh.vertices);
    }

    // Everything inside (iso at the minimum): the closed box of the field of
    // view, its faces half a voxel out, edges and corners chamfered. A single
    // slice gives a closed plate one voxel thick.
    void wholeFieldOfViewAndSingleSlice() {
        const Volume v = integerNoise(12, 3, 9, 2);
        const TriangleMesh box = contour(v, 3.0).mesh;
        verifyClosed(box, "box");
        const MeshReport r = checkMesh(box);
        QCOMPARE(r.components, std::size_t(1));
        QVERIFY(r.volume > 11.0 * 11.0 * 11.0 && r.volume < 12.0 * 12.0 * 12.0);

        VolumeGeometry g;
        g.dims = {30, 20, 1};
        const Volume slice = sampledVolume(g, VoxelType::Float32, [](const glm::dvec3& x) {
            return 6.0 - glm::length(glm::dvec2(x.x - 14.2, x.y - 9.6));
        });
        const TriangleMesh plate = contour(slice, 0.0).mesh;
        verifyClosed(plate, "single slice");
        const double disc = std::numbers::pi * 36.0; // times a thickness of one voxel
        QVERIFY(std::abs(checkMesh(plate).volume / disc - 1.0) < 0.1);
    }

    void clipBoxClosesWhatItCuts() {
        const Volume v = sphereDistance(10.0, 0.5);
        const MeshReport whole = checkMesh(contour(v, 0.0).mesh);
        // Split at voxel plane 23.5 (x): left keeps i <= 23, right i >= 24.
        IsosurfaceOptions o;
        o.clip.hi.x = 23.0;
        const IsosurfaceResult left = extractIsosurface(v, o);
        o.clip = ClipBox{};
        o.clip.lo.x = 23.5; // rounds up to voxel 24
        const IsosurfaceResult right = extractIsosurface(v, o);
        QCOMPARE(left.last.x, 23);
        QCOMPARE(right.first.x, 24);
        verifyClosed(left.mesh, "left half");
        verifyClosed(right.mesh, "right half");
        // Both caps lie on the plane between voxels 23 and 24, so the halves
        // add up to the whole but for the cells the plane crosses.
        const double sum = checkMesh(left.mesh).volume + checkMesh(right.mesh).volume;
        QVERIFY2(std::abs(sum / whole.volume - 1.0) < 2e-3, qPrintable(QString::number(sum)));
        o.clip.lo = glm::dvec3(5.0);
        o.clip.hi = glm::dvec3(4.0);
        const IsosurfaceResult none = extractIsosurface(v, o);
        QVERIFY(none.mesh.empty());
        QCOMPARE(none.warnings.size(), std::size_t(1));
    }

    // A binary ball at h = a/20: the raw mask over-estimates area by ~9 % (and
    // says so); smoothed with sigma = 1 voxel the bias is under 1 %.
    void binaryMasksWarnAndSmoothingRemovesTheBias() {
        const double a = 10.0;
        const Volume mask = binaryBall(a, 0.5);
        const IsosurfaceResult raw = contour(mask, 0.5);
        verifyClosed(raw.mesh, "raw mask");
        QCOMPARE(raw.warnings.size(), std::size_t(1));
        QVERIFY2(raw.warnings[0].find("binary") != std::string::npos, raw.warnings[0].c_str());
        const double rawBias = meshArea(raw.mesh) / sphereArea(a) - 1.0;

        IsosurfaceOptions o;
        o.iso = 0.5;
        o.smoothingSigma = 1.0;
        const IsosurfaceResult smooth = extractIsosurface(mask, o);
        verifyClosed(smooth.mesh, "smoothed mask");
        QVERIFY(smooth.warnings.empty());
        QVERIFY(smooth.smoothMs > 0.0 && smooth.smoothMs <= smooth.extractMs);
        const double smoothBias = meshArea(smooth.mesh) / sphereArea(a) - 1.0;
        const double volumeBias = meshVolume(smooth.mesh) / sphereVolume(a) - 1.0;
        qInfo("area bias: raw %+.4f, smoothed %+.4f (volume %+.4f)", rawBias, smoothBias,
              volumeBias);
        QVERIFY(rawBias > 0.05);
        QVERIFY(std::abs(smoothBias) < 0.01);
    }

    // Smoothing with a clip box through the ball uses the voxels beyond the
    // box: the same mesh as smoothing the whole volume, then clipping.
    void smoothingSeesBeyondTheClipBox() {
        const Volume mask = binaryBall(10.0, 0.5);
        const glm::ivec3 n = mask.dims();
        Volume smoothed(mask.geometry(), VoxelType::Float32);
        std::vector<float> values;
        const VoxelBlock<std::uint16_t> whole{mask.voxels<std::uint16_t>().data(), n, n.x,
                                              std::ptrdiff_t(n.x) * n.y};
        QVERIFY(gaussianBlur(whole, 1.0, values, {}, 0.0, 1.0));
        std::copy(values.begin(), values.end(), smoothed.voxels<float>().begin());

        IsosurfaceOptions o;
        o.iso = 0.5;
        o.clip.lo = {20.0, 9.0, -5.0};
        o.clip.hi = {60.0, 30.0, 26.0};
        const IsosurfaceResult reference = extractIsosurface(smoothed, o);
        o.smoothingSigma = 1.0;
        const IsosurfaceResult clipped = extractIsosurface(mask, o);
        verifyClosed(clipped.mesh, "smoothed and clipped");
        QVERIFY(clipped.mesh.triangles == reference.mesh.triangles);
        QVERIFY(clipped.mesh.vertices == reference.mesh.vertices);
    }

    void sameMeshForAnyThreadCount() {
        const Volume volumes[] = {gaussianNoise(37, 21), sphereDistance(10.0, 0.5),
                                  integerNoise(33, -2, 2, 4)};
        const int threads = omp_get_max_threads();
        for (const Volume& v : volumes) {
            omp_set_num_threads(1);
            const IsosurfaceResult one = contour(v, 0.0);
            omp_set_num_threads(2);
            const IsosurfaceResult two = contour(v, 0.0);
            QCOMPARE(two.threads, 2);
            QVERIFY(one.mesh.triangles == two.mesh.triangles);
            QVERIFY(one.mesh.vertices == two.mesh.vertices);
        }
        omp_set_num_threads(threads);
    }

    void sameMeshForEveryVoxelType() {
        const Volume i16 = integerNoise(24, 0, 9, 3);
        VolumeGeometry g = i16.geometry();
        const auto copyAs = [&](VoxelType type) {
            return sampledVolume(g, type, [&](const glm::dvec3& x) {
                return i16.value(int(x.x), int(x.y), int(x.z));
            });
        };
        for (const double iso : {4.0, 4.5}) {
            const TriangleMesh reference = contour(i16, iso).mesh;
            QVERIFY(reference.triangles.size() > 1000);
            for (const VoxelType type : {VoxelType::UInt16, VoxelType::Float32}) {
                const TriangleMesh mesh = contour(copyAs(type), iso).mesh;
                QVERIFY(mesh.triangles == reference.triangles);
                QVERIFY(mesh.vertices == reference.vertices);
            }
        }
    }

    void vertexPositionsFollowTheFrame() {
        // One voxel above the iso value in a 3^3 volume: an octahedron whose
        // vertices lie at the crossings along the six axes, in LPS.
        VolumeGeometry g;
        g.dims = glm::ivec3(3);
        g.spacing = {0.5, 1.0, 2.0};
        g.origin = {-10.0, 20.0, 30.0};
        Volume v(g, VoxelType::Float32);
        std::fill(v.voxels<float>().begin(), v.voxels<float>().end(), 0.0f);
        v.voxels<float>()[v.linearIndex(1, 1, 1)] = 4.0f;
        const TriangleMesh mesh = contour(v, 1.0).mesh; // t = 1/4 away from the centre voxel
        QCOMPARE(mesh.triangles.size(), std::size_t(8));
        const glm::dvec3 centre = g.toPatient({1, 1, 1});
        for (const glm::dvec3& p : mesh.vertices) {
            const glm::dvec3 offset = (p - centre) / g.spacing;
            QVERIFY(std::abs(glm::length(offset) - 0.75) < 1e-12);
        }
        QVERIFY(checkMesh(mesh).volume > 0.0);
    }

    void isoOutsideTheRangeIsRefused() {
        const Volume v = integerNoise(8, -2, 2, 1);
        try {
            contour(v, 7.25);
            QFAIL("no exception");
        } catch (const std::invalid_argument& e) {
            const std::string what = e.what();
            QVERIFY2(what.find("7.25") != std::string::npos, e.what());
            QVERIFY2(what.find("[-2, 2]") != std::string::npos, e.what());
        }
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, contour(v, std::nan("")));
        IsosurfaceOptions o;
        o.smoothingSigma = -1.0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, extractIsosurface(v, o));
    }

    void progressRisesAndCancelStops() {
        const Volume v = gaussianNoise(40, 9);
        std::vector<double> seen;
        IsosurfaceOptions o;
        o.progress = [&](double f) {
            seen.push_back(f);
            return true;
        };
        const IsosurfaceResult r = extractIsosurface(v, o);
        QVERIFY(!r.mesh.empty());
        QVERIFY(seen.size() >= 3);
        QVERIFY(std::is_sorted(seen.begin(), seen.end()));
        QCOMPARE(seen.back(), 1.0);
        int calls = 0;
        o.progress = [&](double) { return ++calls < 2; };
        QVERIFY_THROWS_EXCEPTION(IsosurfaceCancelled, extractIsosurface(v, o));
        QCOMPARE(calls, 2);
        o.smoothingSigma = 1.0; // cancelled while smoothing
        calls = 0;
        QVERIFY_THROWS_EXCEPTION(IsosurfaceCancelled, extractIsosurface(v, o));
    }
};

QTEST_GUILESS_MAIN(TestIsosurfaceExtractor)
#include "test_isosurface_extractor.moc"
