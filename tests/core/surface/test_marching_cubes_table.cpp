// The generated marching-cubes table: every case separates exactly its cut
// edges, loops close inside the cube, neighbouring cubes agree on their shared
// face, no chord lies in a face, and triangles face away from inside corners.
#include <QTest>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <utility>

#include <glm/glm.hpp>

#include "core/surface/MarchingCubesTable.h"

using namespace lucent;

namespace {

glm::dvec3 cornerPosition(int c) {
    return {c & 1, (c >> 1) & 1, (c >> 2) & 1};
}

glm::dvec3 edgeMidpoint(int e) {
    const auto [a, b] = marchingCubesEdgeCorners(e);
    return 0.5 * (cornerPosition(a) + cornerPosition(b));
}

bool inside(int cubeCase, int c) {
    return ((cubeCase >> c) & 1) != 0;
}

bool isCut(int cubeCase, int e) {
    const auto [a, b] = marchingCubesEdgeCorners(e);
    return inside(cubeCase, a) != inside(cubeCase, b);
}

// Face f = 2 * axis + side.
bool edgeOnFace(int e, int f) {
    const int axis = f / 2;
    const auto [a, b] = marchingCubesEdgeCorners(e);
    return e / 4 != axis && ((a >> axis) & 1) == f % 2 && ((b >> axis) & 1) == f % 2;
}

bool shareFace(int e1, int e2) {
    for (int f = 0; f < 6; ++f) {
        if (edgeOnFace(e1, f) && edgeOnFace(e2, f)) {
            return true;
        }
    }
    return false;
}

// Directed triangle sides (edge pairs) of a case.
std::vector<std::pair<int, int>> sides(const MarchingCubesCase& mc) {
    std::vector<std::pair<int, int>> out;
    for (int t = 0; t < mc.triangleCount; ++t) {
        for (int i = 0; i < 3; ++i) {
            out.emplace_back(mc.edges[3 * t + i], mc.edges[3 * t + (i + 1) % 3]);
        }
    }
    return out;
}

// The sides lying on face f: the segments the case draws there.
std::set<std::pair<int, int>> faceSegments(int cubeCase, int f) {
    std::set<std::pair<int, int>> out;
    for (const auto& [a, b] : sides(marchingCubesCases()[cubeCase])) {
        if (edgeOnFace(a, f) && edgeOnFace(b, f)) {
            out.emplace(a, b);
        }
    }
    return out;
}

// The edge of the neighbour across face (axis, side 1) that coincides with
// edge e of this cube: the same edge with the axis coordinate flipped.
int acrossFace(int e, int axis) {
    const int flippedLow = marchingCubesEdgeCorners(e)[0] ^ (1 << axis);
    for (int f = 0; f < 12; ++f) {
        if (f / 4 == e / 4 && marchingCubesEdgeCorners(f)[0] == flippedLow) {
            return f;
        }
    }
    return -1;
}

} // namespace

class TestMarchingCubesTable : public QObject {
    Q_OBJECT

private slots:
    void totalIs820() {
        int total = 0;
        for (const MarchingCubesCase& mc : marchingCubesCases()) {
            total += mc.triangleCount;
        }
        QCOMPARE(total, 820);
        QCOMPARE(int(marchingCubesCases()[0].triangleCount), 0);
        QCOMPARE(int(marchingCubesCases()[255].triangleCount), 0);
    }

    void edgeNumbering() {
        // x edges at (y, z) = (0,0) (1,0) (0,1) (1,1), then y and z edges likewise.
        QCOMPARE((marchingCubesEdgeCorners(0)), (std::array<int, 2>{0, 1}));
        QCOMPARE((marchingCubesEdgeCorners(3)), (std::array<int, 2>{6, 7}));
        QCOMPARE((marchingCubesEdgeCorners(5)), (std::array<int, 2>{1, 3}));
        QCOMPARE((marchingCubesEdgeCorners(6)), (std::array<int, 2>{4, 6}));
        QCOMPARE((marchingCubesEdgeCorners(9)), (std::array<int, 2>{1, 5}));
        QCOMPARE((marchingCubesEdgeCorners(10)), (std::array<int, 2>{2, 6}));
    }

    void trianglesUseExactlyTheCutEdges() {
        for (int c = 0; c < 256; ++c) {
            const MarchingCubesCase& mc = marchingCubesCases()[c];
            std::set<int> used;
            for (int t = 0; t < mc.triangleCount; ++t) {
                const int a = mc.edges[3 * t], b = mc.edges[3 * t + 1], d = mc.edges[3 * t + 2];
                QVERIFY2(a != b && b != d && d != a, qPrintable(QString("case %1").arg(c)));
                used.insert({a, b, d});
            }
            std::set<int> cut;
            for (int e = 0; e < 12; ++e) {
                if (isCut(c, e)) {
                    cut.insert(e);
                }
            }
            QVERIFY2(used == cut, qPrintable(QString("case %1").arg(c)));
        }
    }

    // Inside the cube every side is shared by two triangles in opposite
    // directions; a side on a face belongs to one triangle (the neighbour has
    // the other). No side joins two edges of one face unless it is such a
    // segment (the chord rule).
    void loopsCloseAndChordsAvoidFaces() {
        for (int c = 0; c < 256; ++c) {
            std::map<std::pair<int, int>, int> directed;
            for (const auto& s : sides(marchingCubesCases()[c])) {
                ++directed[s];
            }
            for (const auto& [s, n] : directed) {
                const int reverse =
                    directed.count({s.second, s.first}) ? directed[{s.second, s.first}] : 0;
                const QString where =
                    QString("case %1 side %2-%3").arg(c).arg(s.first).arg(s.second);
                QVERIFY2(n == 1, qPrintable(where + " repeated"));
                if (shareFace(s.first, s.second)) {
                    QVERIFY2(reverse == 0, qPrintable(where + " is a chord in a face"));
                } else {
                    QVERIFY2(reverse == 1, qPrintable(where + " is not closed"));
                }
            }
        }
    }

    // For every case and every neighbour pattern across each face, the two
    // cubes draw the same segments on the shared face, in opposite directions.
    void neighboursAgreeOnSharedFaces() {
        for (int axis = 0; axis < 3; ++axis) {
            for (int c = 0; c < 256; ++c) {
                for (int other = 0; other < 16; ++other) {
                    // Neighbour's low face (side 0) copies this cube's high face.
                    int neighbour = 0, o = 0;
                    for (int k = 0; k < 8; ++k) {
                        const bool low = ((k >> axis) & 1) == 0;
                        const bool in =
                            low ? inside(c, k | (1 << axis)) : ((other >> o++) & 1) != 0;
                        neighbour |= in ? 1 << k : 0;
                    }
                    std::set<std::pair<int, int>> mapped;
                    for (const auto& [a, b] : faceSegments(c, 2 * axis + 1)) {
                        mapped.emplace(acrossFace(b, axis), acrossFace(a, axis));
                    }
                    QVERIFY2(mapped == faceSegments(neighbour, 2 * axis),
                             qPrintable(QString("axis %1 case %2 neighbour %3")
                                            .arg(axis)
                                            .arg(c)
                                            .arg(neighbour)));
                }
            }
        }
    }

    void ambiguousFacesSeparateInsideCorners() {
        // Corners 0 and 3 inside: face z = 0 is ambiguous; each corner is cut off alone.
        QCOMPARE(int(marchingCubesCases()[(1 << 0) | (1 << 3)].triangleCount), 2);
        // Four corners no two of which share an edge: four separate corners.
        QCOMPARE(int(marchingCubesCases()[(1 << 0) | (1 << 3) | (1 << 5) | (1 << 6)].triangleCount),
                 4);
        QCOMPARE(int(marchingCubesCases()[(1 << 1) | (1 << 2) | (1 << 4) | (1 << 7)].triangleCount),
                 4);
    }

    void singleCornerFacesAway_data() {
        QTest::addColumn<int>("corner");
        for (int c = 0; c < 8; ++c) {
            QTest::newRow(qPrintable(QString("corner %1").arg(c))) << c;
        }
    }
    void singleCornerFacesAway() {
        QFETCH(int, corner);
        for (const bool complement : {false, true}) {
            const int cubeCase = complement ? 255 ^ (1 << corner) : 1 << corner;
            const MarchingCubesCase& mc = marchingCubesCases()[cubeCase];
            QCOMPARE(int(mc.triangleCount), 1);
            const glm::dvec3 p0 = edgeMidpoint(mc.edges[0]);
            const glm::dvec3 p1 = edgeMidpoint(mc.edges[1]);
            const glm::dvec3 p2 = edgeMidpoint(mc.edges[2]);
            const glm::dvec3 normal = glm::cross(p1 - p0, p2 - p0);
            const glm::dvec3 away = (p0 + p1 + p2) / 3.0 - cornerPosition(corner);
            // Inside corner alone: the normal leaves it; outside corner alone: it points at it.
            QVERIFY(complement ? glm::dot(normal, away) < 0.0 : glm::dot(normal, away) > 0.0);
        }
    }
};

QTEST_GUILESS_MAIN(TestMarchingCubesTable)
#include "test_marching_cubes_table.moc"
