// The mesh checks on small meshes whose defects are known: each count must
// see exactly the defect built into the mesh, and nothing on a clean one.
#include <QTest>

#include <chrono>
#include <stdexcept>

#include "core/surface/IsosurfaceExtractor.h"
#include "core/surface/MeshChecks.h"
#include "tests/core/surface/IsoVolumes.h"

using namespace lucent;

namespace {

// The corner tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), normals out.
TriangleMesh tetrahedron(glm::dvec3 offset = glm::dvec3(0.0)) {
    TriangleMesh m;
    m.vertices = {offset, offset + glm::dvec3(1, 0, 0), offset + glm::dvec3(0, 1, 0),
                  offset + glm::dvec3(0, 0, 1)};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return m;
}

// b's vertices appended to a's, b's triangles renumbered.
TriangleMesh joined(const TriangleMesh& a, const TriangleMesh& b) {
    TriangleMesh m = a;
    const auto base = static_cast<std::uint32_t>(a.vertices.size());
    m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
    for (const glm::u32vec3& t : b.triangles) {
        m.triangles.push_back(t + base);
    }
    return m;
}

} // namespace

class TestMeshChecks : public QObject {
    Q_OBJECT

private slots:
    void cleanTetrahedron() {
        const MeshReport r = checkMesh(tetrahedron());
        QVERIFY(r.closedManifold());
        QCOMPARE(r.triangles, std::size_t(4));
        QCOMPARE(r.vertices, std::size_t(4));
        QCOMPARE(r.edges, std::size_t(6));
        QCOMPARE(r.euler, 2LL);
        QCOMPARE(r.components, std::size_t(1));
        QCOMPARE(r.zeroAreaTriangles, std::size_t(0));
        QVERIFY(std::abs(r.volume - 1.0 / 6.0) < 1e-15);
        QVERIFY(std::abs(r.area - (1.5 + std::sqrt(3.0) / 2.0)) < 1e-15);
        QVERIFY(std::abs(r.hMax - std::sqrt(2.0)) < 1e-15);
        QCOMPARE(meshVolume(tetrahedron()), r.volume);
        QCOMPARE(meshArea(tetrahedron()), r.area);
    }

    void farFromTheOriginKeepsItsVolume() {
        const MeshReport r = checkMesh(tetrahedron(glm::dvec3(-3e4, 2e4, 1e5)));
        QVERIFY(std::abs(r.volume - 1.0 / 6.0) < 1e-9);
        QVERIFY(std::abs(meshVolume(tetrahedron(glm::dvec3(-3e4, 2e4, 1e5))) - 1.0 / 6.0) < 1e-9);
    }

    void insideOutHasNegativeVolume() {
        TriangleMesh m = tetrahedron();
        for (glm::u32vec3& t : m.triangles) {
            std::swap(t[1], t[2]);
        }
        const MeshReport r = checkMesh(m);
        QVERIFY(r.closedManifold());
        QVERIFY(std::abs(r.volume + 1.0 / 6.0) < 1e-15);
    }

    void oneFlippedTriangleRepeatsEdges() {
        TriangleMesh m = tetrahedron();
        std::swap(m.triangles[3][1], m.triangles[3][2]);
        const MeshReport r = checkMesh(m);
        QVERIFY(r.watertight());
        QCOMPARE(r.repeatedDirectedEdges, std::size_t(3));
        QVERIFY(!r.closedManifold());
    }

    void missingTriangleLeavesBoundary() {
        TriangleMesh m = tetrahedron();
        m.triangles.pop_back();
        const MeshReport r = checkMesh(m);
        QCOMPARE(r.boundaryEdges, std::size_t(3));
        QCOMPARE(r.nonManifoldVertices, std::size_t(0)); // an open fan is still one fan
        QVERIFY(!r.watertight());
        QCOMPARE(r.euler, 1LL);
    }

    void finMakesANonManifoldEdge() {
        TriangleMesh m = tetrahedron();
        m.vertices.push_back({1, 1, -1});
        m.triangles.push_back({0, 1, 4}); // a third triangle on edge 0-1
        const MeshReport r = checkMesh(m);
        QCOMPARE(r.nonManifoldEdges, std::size_t(1));
        QCOMPARE(r.boundaryEdges, std::size_t(2));
        QVERIFY(!r.watertight());
    }

    // Two tetrahedra meeting only at the origin: closed, but pinched there.
    void pinchedVertexIsNonManifold() {
        TriangleMesh mirrored = tetrahedron();
        for (glm::dvec3& v : mirrored.vertices) {
            v = -v; // a point reflection turns the normals inwards...
        }
        for (glm::u32vec3& t : mirrored.triangles) {
            std::swap(t[1], t[2]); // ...so turn them back out
        }
        TriangleMesh pinch = joined(tetrahedron(), mirrored);
        QCOMPARE(checkMesh(pinch).components, std::size_t(2)); // two origins, by index
        for (glm::u32vec3& t : pinch.triangles) {
            for (int c = 0; c < 3; ++c) {
                t[c] = t[c] == 4 ? 0 : t[c]; // now one shared origin
            }
        }
        const MeshReport r = checkMesh(pinch);
        QVERIFY(r.watertight());
        QCOMPARE(r.nonManifoldVertices, std::size_t(1));
        QCOMPARE(r.components, std::size_t(1));
        QCOMPARE(r.unusedVertices, std::size_t(1));
        QVERIFY(std::abs(r.volume - 2.0 / 6.0) < 1e-15);
    }

    void degenerateTrianglesHaveZeroArea() {
        TriangleMesh m = tetrahedron();
        m.vertices.push_back({2, 0, 0}); // on the line of vertices 0 and 1
        m.triangles.push_back({0, 1, 4});
        m.triangles.push_back({2, 2, 3});
        const MeshReport r = checkMesh(m);
        QCOMPARE(r.zeroAreaTriangles, std::size_t(2));
    }

    void badIndexIsRefused() {
        TriangleMesh m = tetrahedron();
        m.triangles.push_back({0, 1, 9});
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, checkMesh(m));
    }

    // About a million triangles: the sort-based check holds at that size. Its
    // time is printed, not asserted (a sanitizer build or a busy machine is
    // slower; speed belongs to the benchmarks).
    void largeMeshIsChecked() {
        const Volume noise = test::gaussianNoise(76, 4);
        IsosurfaceOptions o;
        const TriangleMesh mesh = extractIsosurface(noise, o).mesh;
        QVERIFY(mesh.triangles.size() > 900000);
        const auto start = std::chrono::steady_clock::now();
        const MeshReport r = checkMesh(mesh);
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        qInfo("%zu triangles checked in %.2f s", r.triangles, s);
        QVERIFY(r.closedManifold());
    }
};

QTEST_GUILESS_MAIN(TestMeshChecks)
#include "test_mesh_checks.moc"
