// The SVR field on polyhedra with closed-form answers (cube, slab), its
// invariances, its independence of the thread count, bad input, cancelling,
// and the statistics of a field.
#include <QTest>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <omp.h>

#include "core/surface/FieldStats.h"
#include "core/surface/SphereIntegrals.h"
#include "core/surface/SurfaceToVolume.h"
#include "core/surface/VertexRings.h"
#include "tests/core/surface/TestMeshes.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr double kPi = std::numbers::pi;

bool near(double value, double expected, double relative) {
    return std::abs(value - expected) <= relative * std::abs(expected);
}

QString mismatch(double value, double expected) {
    return QString("%1 vs %2").arg(value, 0, 'g', 17).arg(expected, 0, 'g', 17);
}

// The cube [0, 2]³ cut into 4 × 4 squares a face: 192 triangles.
TriangleMesh cube() {
    return boxMesh(glm::dvec3(0.0), glm::dvec3(2.0), glm::ivec3(4));
}

// Σ_T Ω_T over the whole mesh, seen from vertex v: the generalised winding number.
double globalSolidAngle(const TriangleMesh& mesh, std::uint32_t v) {
    const glm::dvec3 x = mesh.vertices[v];
    double sum = 0.0;
    for (const glm::u32vec3& t : mesh.triangles) {
        sum += triangleSolidAngle(mesh.vertices[t.x] - x, mesh.vertices[t.y] - x,
                                  mesh.vertices[t.z] - x);
    }
    return sum;
}

SvrField svrAt(const TriangleMesh& mesh, double radius, std::vector<std::uint32_t> vertices) {
    return computeSvrAt(mesh, radius, vertices);
}

template <class F> QString errorOf(F&& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return QString::fromStdString(e.what());
    }
    return {};
}

} // namespace

class TestSurfaceToVolume : public QObject {
    Q_OBJECT
private slots:
    void interiorSolidAnglesOfTheCubeComeFromTheRing() {
        const TriangleMesh mesh = cube();
        const VertexRings rings(mesh);
        std::vector<std::uint32_t> scratch;
        const std::uint32_t face = nearestVertex(mesh, {1, 1, 2});
        const std::uint32_t edge = nearestVertex(mesh, {1, 0, 2});
        const std::uint32_t corner = nearestVertex(mesh, {2, 2, 2});
        QVERIFY(std::abs(*rings.interiorSolidAngle(face, scratch) - 2 * kPi) < 1e-14);
        QVERIFY(std::abs(*rings.interiorSolidAngle(edge, scratch) - kPi) < 1e-14);
        QVERIFY(std::abs(*rings.interiorSolidAngle(corner, scratch) - kPi / 2) < 1e-14);
        for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) {
            const double local = *rings.interiorSolidAngle(v, scratch);
            QVERIFY(std::abs(local - globalSolidAngle(mesh, v)) < 1e-12);
        }
    }

    void twoCubesTouchingAtACornerAddTheirCones() {
        // The shared corner has two closed fans, one per cube: Ω_int = π/2 + π/2.
        TriangleMesh mesh = cube();
        const TriangleMesh other = boxMesh(glm::dvec3(2.0), glm::dvec3(2.0), glm::ivec3(4));
        const std::uint32_t shared = nearestVertex(mesh, glm::dvec3(2.0));
        const std::uint32_t otherCorner = nearestVertex(other, glm::dvec3(2.0));
        const std::uint32_t offset = std::uint32_t(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), other.vertices.begin(), other.vertices.end());
        for (glm::u32vec3 t : other.triangles) {
            for (int k = 0; k < 3; ++k) {
                t[k] = t[k] == otherCorner ? shared : t[k] + offset;
            }
            mesh.triangles.push_back(t);
        }
        const VertexRings rings(mesh);
        std::vector<std::uint32_t> scratch;
        QVERIFY(std::abs(*rings.interiorSolidAngle(shared, scratch) - kPi) < 1e-14);
        QVERIFY(std::abs(globalSolidAngle(mesh, shared) - kPi) < 1e-12);
        const double r = 0.7;
        const SvrField f = svrAt(mesh, r, {shared});
        QVERIFY(near(f.area[0], 1.5 * kPi * r * r, 1e-12));
        QVERIFY(near(f.volume[0], kPi * r * r * r / 3, 1e-12));
        QVERIFY(near(f.svr[0], 9 / (2 * r), 1e-12));
    }

    void cubeFaceEdgeAndCornerMatchTheClosedForms() {
        const TriangleMesh mesh = cube();
        QCOMPARE(mesh.triangles.size(), std::size_t(192));
        const double r = 0.7;
        const SvrField f = svrAt(mesh, r,
                                 {nearestVertex(mesh, {1, 1, 2}), nearestVertex(mesh, {1, 0, 2}),
                                  nearestVertex(mesh, {2, 2, 2})});
        const double expected[] = {3 / (2 * r), 3 / r, 9 / (2 * r)};
        for (int i = 0; i < 3; ++i) {
            QVERIFY2(near(f.svr[i], expected[i], 1e-12),
                     qPrintable(mismatch(f.svr[i], expected[i])));
        }
        QVERIFY(near(f.area[0], kPi * r * r, 1e-12));
        QVERIFY(near(f.volume[0], 2 * kPi * r * r * r / 3, 1e-12));
        QCOMPARE(f.unusedVertices, std::size_t(0));
    }

    void aRotatedCubeSeenByASmallBallKeepsItsClosedForms() {
        // R below the edge length puts the triangles around X on the clip path,
        // and the rotation gives their h rounding noise instead of exact zeros.
        const double c = std::cos(0.4), s = std::sin(0.4);
        const glm::dmat3 m =
            glm::dmat3(c, s, 0, -s, c, 0, 0, 0, 1) * glm::dmat3(c, 0, -s, 0, 1, 0, s, 0, c);
        const TriangleMesh base = cube();
        const TriangleMesh mesh = transformed(base, m, {3.7, -1.2, 0.4});
        const double r = 0.3;
        const SvrField f = svrAt(mesh, r,
                                 {nearestVertex(base, {1, 1, 2}), nearestVertex(base, {1, 0, 2}),
                                  nearestVertex(base, {2, 2, 2})});
        const double expected[] = {3 / (2 * r), 3 / r, 9 / (2 * r)};
        for (int i = 0; i < 3; ++i) {
            QVERIFY2(near(f.svr[i], expected[i], 1e-12),
                     qPrintable(mismatch(f.svr[i], expected[i])));
        }
    }

    void aBallHoldingTheCubeGivesItsWholeRatio() {
        const TriangleMesh mesh = cube();
        const SvrField f = computeSvrField(mesh, 10.0);
        QVERIFY(near(f.totalArea, 24.0, 1e-14) && near(f.totalVolume, 8.0, 1e-14));
        QVERIFY(near(f.totalRatio, 3.0, 1e-14));
        QCOMPARE(f.longestEdge, std::sqrt(0.5));
        QCOMPARE(f.longestEdgeOverRadius, std::sqrt(0.5) / 10.0);
        for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
            QVERIFY2(near(f.area[v], 24.0, 1e-12), qPrintable(mismatch(f.area[v], 24.0)));
            QVERIFY2(near(f.volume[v], 8.0, 1e-12), qPrintable(mismatch(f.volume[v], 8.0)));
            QVERIFY(near(f.svr[v], 3.0, 1e-12)); // 6/L
        }
    }

    void aBallReachingTheSideFacesHasTheAnalyticVolume() {
        const TriangleMesh mesh = cube();
        const SvrField f = svrAt(mesh, 1.3, {nearestVertex(mesh, {1, 1, 2})});
        // Half ball minus four half caps of height 0.3.
        const double capHeight = 0.3, r = 1.3;
        const double halfCap = 0.5 * kPi * capHeight * capHeight * (3 * r - capHeight) / 3;
        const double analytic = 2 * kPi * r * r * r / 3 - 4 * halfCap;
        QVERIFY(std::abs(analytic - 3.9228020267824544) < 1e-14);
        QVERIFY2(std::abs(f.volume[0] - 3.9228020267824544) < 1e-12,
                 qPrintable(mismatch(f.volume[0], 3.9228020267824544)));
    }

    void slabFaceCentreFollowsTheSlabFormula_data() {
        QTest::addColumn<double>("radius");
        QTest::addColumn<double>("expected");
        const double t = 2.0;
        auto formula = [t](double r) { return (2 * r * r - t * t) / (r * r * t - t * t * t / 3); };
        QTest::newRow("R=1") << 1.0 << 1.5;
        QTest::newRow("R=2") << 2.0 << 0.75;
        QTest::newRow("R=3") << 3.0 << 0.913043478261;
        QTest::newRow("R=5") << 5.0 << formula(5.0);
        QTest::newRow("R=9") << 9.0 << 0.991631799163;
        QVERIFY(near(formula(5.0), 0.971830985915, 1e-12));
        QVERIFY(near(formula(3.0), 0.913043478261, 1e-12));
    }
    void slabFaceCentreFollowsTheSlabFormula() {
        QFETCH(double, radius);
        QFETCH(double, expected);
        const TriangleMesh slab = boxMesh({-10, -10, 0}, {20, 20, 2}, {10, 10, 2});
        const SvrField f = svrAt(slab, radius, {nearestVertex(slab, {0, 0, 2})});
        // The note's values carry 12 digits: compare at that precision.
        QVERIFY2(std::abs(f.svr[0] - expected) < 1e-12, qPrintable(mismatch(f.svr[0], expected)));
    }

    void rigidMotionsLeaveTheFieldAndScalingScalesIt() {
        const TriangleMesh base = torus(10.0, 3.0, 64, 24);
        const double radius = 2.0;
        const SvrField reference = computeSvrField(base, radius);
        const double c = std::cos(0.7), s = std::sin(0.7);
        const glm::dmat3 rotation =
            glm::dmat3(c, s, 0, -s, c, 0, 0, 0, 1) *
            glm::dmat3(1, 0, 0, 0, std::cos(1.1), std::sin(1.1), 0, -std::sin(1.1), std::cos(1.1));
        const SvrField moved =
            computeSvrField(transformed(base, rotation, {123.4, -56.7, 890.1}), radius);
        const double lambda = 0.37;
        const SvrField scaled =
            computeSvrField(transformed(base, glm::dmat3(lambda), {}), lambda * radius);
        double worstMoved = 0.0, worstScaled = 0.0;
        for (std::size_t v = 0; v < base.vertices.size(); ++v) {
            const double ref = reference.svr[v];
            worstMoved = std::max(worstMoved, std::abs(moved.svr[v] - ref) / ref);
            worstScaled = std::max(worstScaled, std::abs(scaled.svr[v] * lambda - ref) / ref);
        }
        QVERIFY2(worstMoved <= 1e-10, qPrintable(QString::number(worstMoved)));
        QVERIFY2(worstScaled <= 1e-12, qPrintable(QString::number(worstScaled)));
    }

    void theFieldDoesNotDependOnTheThreadCount() {
        const TriangleMesh mesh = icosphere(10.0, 4);
        const int before = omp_get_max_threads();
        omp_set_num_threads(1);
        const SvrField one = computeSvrField(mesh, 3.0);
        omp_set_num_threads(2);
        const SvrField two = computeSvrField(mesh, 3.0);
        omp_set_num_threads(before);
        QCOMPARE(one.threads, 1);
        QCOMPARE(two.threads, 2);
        QVERIFY(one.svr == two.svr && one.area == two.area && one.volume == two.volume);
        QCOMPARE(one.candidatesPerQuery, two.candidatesPerQuery);
        QCOMPARE(one.clippedPerQuery, two.clippedPerQuery);
    }

    void aGridOfCellRGivesTheSameFieldAsCellRHalf() {
        const TriangleMesh mesh = torus(10.0, 3.0, 48, 16);
        SvrOptions coarse, fine;
        coarse.cellSizeOverRadius = 1.0;
        fine.cellSizeOverRadius = 0.5;
        const SvrField a = computeSvrField(mesh, 2.5, coarse);
        const SvrField b = computeSvrField(mesh, 2.5, fine);
        for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
            QVERIFY(near(a.svr[v], b.svr[v], 1e-13));
        }
        QVERIFY(b.candidatesPerQuery < a.candidatesPerQuery);
        QCOMPARE(a.clippedPerQuery, b.clippedPerQuery);
    }

    void badInputIsRefusedByName() {
        const TriangleMesh mesh = cube();
        QVERIFY(errorOf([&] { computeSvrField(mesh, 0.0); }).contains("radius"));
        QVERIFY(errorOf([&] { computeSvrField(mesh, -1.5); }).contains("-1.5"));
        QVERIFY(errorOf([&] { computeSvrField(mesh, std::nan("")); }).contains("nan"));
        QVERIFY(errorOf([&] { computeSvrField(mesh, INFINITY); }).contains("inf"));
        QVERIFY(errorOf([&] { computeSvrField(TriangleMesh{}, 1.0); }).contains("empty"));
        TriangleMesh open = mesh;
        open.triangles.pop_back();
        QVERIFY(errorOf([&] { computeSvrField(open, 1.0); }).contains("not closed"));
        TriangleMesh flipped = mesh;
        std::swap(flipped.triangles[3].y, flipped.triangles[3].z);
        QVERIFY(errorOf([&] { computeSvrField(flipped, 1.0); }).contains("not closed"));
        TriangleMesh badIndex = mesh;
        badIndex.triangles[5].y = 100000;
        QVERIFY(errorOf([&] { computeSvrField(badIndex, 1.0); }).contains("triangle 5"));
        TriangleMesh badVertex = mesh;
        badVertex.vertices[7].z = NAN;
        QVERIFY(errorOf([&] { computeSvrField(badVertex, 1.0); }).contains("vertex 7"));
        QVERIFY(errorOf([&] { svrAt(mesh, 1.0, {9999}); }).contains("9999"));
        SvrOptions noCells;
        noCells.cellSizeOverRadius = 0.0;
        QVERIFY(errorOf([&] { computeSvrField(mesh, 1.0, noCells); }).contains("cell"));
    }

    void anUnusedVertexGetsNoValue() {
        TriangleMesh mesh = cube();
        mesh.vertices.push_back({5, 5, 5});
        const SvrField f = computeSvrField(mesh, 0.7);
        QCOMPARE(f.unusedVertices, std::size_t(1));
        QVERIFY(std::isnan(f.svr.back()));
        QVERIFY(std::isfinite(f.svr.front()));
    }

    void progressReportsAndCancelStops() {
        const TriangleMesh mesh = icosphere(10.0, 4); // 2562 vertices
        std::vector<double> fractions;
        SvrOptions watch;
        watch.threads = 1;
        watch.progress = [&](double done) { return fractions.push_back(done), true; };
        const SvrField whole = computeSvrField(mesh, 2.0, watch);
        QVERIFY(fractions.size() >= 20 && fractions.size() <= 101);
        QVERIFY(std::is_sorted(fractions.begin(), fractions.end()));
        QVERIFY(fractions.front() > 0.0 && fractions.back() < 1.0);

        int calls = 0;
        SvrOptions cancel;
        cancel.progress = [&](double) { return ++calls < 3; };
        QVERIFY_THROWS_EXCEPTION(SvrCancelled, computeSvrField(mesh, 2.0, cancel));
        QCOMPARE(calls, 3);

        SvrOptions failing;
        failing.progress = [](double) -> bool { throw std::logic_error("from the hook"); };
        QVERIFY_THROWS_EXCEPTION(std::logic_error, computeSvrField(mesh, 2.0, failing));
        // A cancelled run leaves nothing behind: the next one is whole and equal.
        QVERIFY(computeSvrField(mesh, 2.0).svr == whole.svr);
    }

    void fieldStatsLeaveOutNonFiniteValues() {
        std::vector<double> values;
        for (int i = 1; i <= 100; ++i) {
            values.push_back(i);
        }
        values.push_back(NAN);
        values.push_back(INFINITY);
        const FieldStats s = fieldStats(values);
        QCOMPARE(s.count, std::size_t(100));
        QCOMPARE(s.nonFinite, std::size_t(2));
        QCOMPARE(s.mean, 50.5);
        QVERIFY(near(s.p05, 5.95, 1e-14) && near(s.p50, 50.5, 1e-14) && near(s.p95, 95.05, 1e-14));
        QCOMPARE(s.min, 1.0);
        QCOMPARE(s.max, 100.0);
        QCOMPARE(statsLine("svr", s), std::string("svr_mean=50.5 svr_p05=5.95 svr_p50=50.5 "
                                                  "svr_p95=95.05 svr_min=1 svr_max=100 svr_n=100"));
        QCOMPARE(fieldStats(std::vector<double>{NAN}).count, std::size_t(0));
    }
};

QTEST_GUILESS_MAIN(TestSurfaceToVolume)
#include "test_surface_to_volume.moc"
