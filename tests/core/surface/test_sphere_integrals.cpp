// The exact kernels of the method of spheres (area and solid angle of a
// triangle inside a ball) against independent computations, and the grid that
// hands them their candidates.
#include <QTest>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include "core/surface/SphereIntegrals.h"
#include "core/surface/TriangleGrid.h"

using namespace lucent;

namespace {

constexpr double kPi = std::numbers::pi;

// A plane polygon as 2-D coordinates in the basis (u, v) about a centre.
using Polygon = std::vector<glm::dvec2>;

// Sutherland–Hodgman: keeps the part of `poly` left of the directed line a → b.
Polygon clipLeftOf(const Polygon& poly, glm::dvec2 a, glm::dvec2 b) {
    auto side = [&](glm::dvec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); };
    Polygon out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec2 p = poly[i], q = poly[(i + 1) % poly.size()];
        const double sp = side(p), sq = side(q);
        if (sp >= 0.0) {
            out.push_back(p);
        }
        if ((sp >= 0.0) != (sq >= 0.0)) {
            out.push_back(p + (q - p) * (sp / (sp - sq)));
        }
    }
    return out;
}

double polygonArea(const Polygon& poly) {
    double twice = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec2 p = poly[i], q = poly[(i + 1) % poly.size()];
        twice += p.x * q.y - p.y * q.x;
    }
    return 0.5 * twice;
}

// Area and signed solid angle (seen from X) of T ∩ (regular N-gon of circumradius
// rho about the disc centre): with the inscribed and the circumscribed N-gon of
// the disc they bracket the exact values, for an oracle with no arcs in it.
struct PolygonPart {
    double area = 0.0, solidAngle = 0.0;
};

PolygonPart triangleAndNgon(const std::array<glm::dvec3, 3>& p, glm::dvec3 x, double radius, int n,
                            bool circumscribed) {
    glm::dvec3 normal = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
    const double h = glm::dot(normal, p[0] - x);
    const glm::dvec3 centre = x + h * normal;
    const double r = std::sqrt(radius * radius - h * h);
    const double rho = circumscribed ? r / std::cos(kPi / n) : r;
    const glm::dvec3 u = glm::normalize(
        glm::cross(normal, std::abs(normal.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 v = glm::cross(normal, u);
    Polygon poly;
    for (int k = 0; k < n; ++k) {
        poly.push_back(rho * glm::dvec2(std::cos(2 * kPi * k / n), std::sin(2 * kPi * k / n)));
    }
    std::array<glm::dvec2, 3> t;
    for (int i = 0; i < 3; ++i) {
        t[i] = {glm::dot(p[i] - centre, u), glm::dot(p[i] - centre, v)};
    }
    for (int i = 0; i < 3 && !poly.empty(); ++i) {
        poly = clipLeftOf(poly, t[i], t[(i + 1) % 3]);
    }
    PolygonPart part;
    if (poly.size() < 3) {
        return part;
    }
    part.area = polygonArea(poly);
    auto lift = [&](glm::dvec2 q) { return centre + q.x * u + q.y * v - x; };
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
        part.solidAngle += triangleSolidAngle(lift(poly[0]), lift(poly[i]), lift(poly[i + 1]));
    }
    return part;
}

glm::dvec3 randomPoint(std::mt19937_64& rng, double extent) {
    std::uniform_real_distribution<double> d(-extent, extent);
    return {d(rng), d(rng), d(rng)};
}

glm::dmat3 randomRotation(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    const glm::dvec3 a = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
    glm::dvec3 b = glm::dvec3(g(rng), g(rng), g(rng));
    b = glm::normalize(b - glm::dot(a, b) * a);
    return glm::dmat3(a, b, glm::cross(a, b));
}

} // namespace

class TestSphereIntegrals : public QObject {
    Q_OBJECT
private slots:
    void aTriangleInsideTheBallGivesItsArea() {
        std::mt19937_64 rng(7);
        for (int i = 0; i < 200; ++i) {
            const glm::dvec3 x = randomPoint(rng, 5.0);
            const PreparedTriangle t = prepareTriangle(
                x + randomPoint(rng, 0.5), x + randomPoint(rng, 0.5), x + randomPoint(rng, 0.5));
            const Ball ball(x, 0.9);
            const BallContribution c = ballContribution(t, ball);
            QCOMPARE(int(c.path), int(BallPath::Inside));
            QCOMPARE(c.area, t.area);
            const double expectedArea = 0.5 * glm::length(glm::cross(t.p1 - t.p0, t.p2 - t.p0));
            QVERIFY(std::abs(c.area - expectedArea) <= 1e-15 * expectedArea);
        }
    }

    void clippedAreaAndSolidAngleLieBetweenInscribedAndCircumscribedPolygons() {
        std::mt19937_64 rng(11);
        std::uniform_real_distribution<double> size(0.2, 6.0), radius(0.1, 3.0);
        constexpr int n = 4096;
        int clipped = 0, discInside = 0, chords = 0, inside = 0;
        for (int i = 0; i < 3000; ++i) {
            const double s = size(rng);
            const std::array<glm::dvec3, 3> p{randomPoint(rng, s), randomPoint(rng, s),
                                              randomPoint(rng, s)};
            const Ball ball(randomPoint(rng, 1.5), radius(rng));
            const PreparedTriangle t = prepareTriangle(p[0], p[1], p[2]);
            const BallContribution c = ballContribution(t, ball);
            BallSums sums(ball);
            sums.add(t);
            QCOMPARE(sums.area(), c.area);
            const double h = glm::dot(t.normal, t.p0 - ball.centre);
            if (std::abs(h) >= ball.radius) {
                QCOMPARE(c.area, 0.0);
                continue;
            }
            const PolygonPart lo = triangleAndNgon(p, ball.centre, ball.radius, n, false);
            const PolygonPart hi = triangleAndNgon(p, ball.centre, ball.radius, n, true);
            const double slack = 1e-12 * (1.0 + hi.area);
            QVERIFY2(lo.area - slack <= c.area && c.area <= hi.area + slack,
                     qPrintable(QString("case %1: %2 not in [%3, %4]")
                                    .arg(i)
                                    .arg(c.area, 0, 'g', 17)
                                    .arg(lo.area, 0, 'g', 17)
                                    .arg(hi.area, 0, 'g', 17)));
            const double omega = std::copysign(1.0, h) * sums.solidAngle();
            const double omegaLo = std::copysign(1.0, h) * lo.solidAngle;
            const double omegaHi = std::copysign(1.0, h) * hi.solidAngle;
            QVERIFY2(omegaLo - 1e-9 <= omega && omega <= omegaHi + 1e-9,
                     qPrintable(QString("case %1: solid angle %2 not in [%3, %4]")
                                    .arg(i)
                                    .arg(omega, 0, 'g', 17)
                                    .arg(omegaLo, 0, 'g', 17)
                                    .arg(omegaHi, 0, 'g', 17)));
            QVERIFY(hi.area - lo.area <= 1e-5 * ball.radius2);
            const bool disc = std::abs(c.area - kPi * (ball.radius2 - h * h)) < 1e-12;
            clipped += c.path == BallPath::Clipped;
            inside += c.path == BallPath::Inside;
            discInside += c.path == BallPath::Clipped && disc;
            chords += c.path == BallPath::Clipped && !disc && c.area > 0.0;
        }
        // Every path of the kernel was exercised, each many times.
        QVERIFY2(inside > 50 && discInside > 50 && chords > 300,
                 qPrintable(QString("inside %1, disc %2, chords %3 of %4 clipped")
                                .arg(inside)
                                .arg(discInside)
                                .arg(chords)
                                .arg(clipped)));
    }

    void aCubeFaceSubtendsOneSixthOfTheSphereFromTheCentre() {
        // Face z = +1 of the cube [-1, 1]³, wound CCW seen from outside.
        const glm::dvec3 a(-1, -1, 1), b(1, -1, 1), c(1, 1, 1), d(-1, 1, 1);
        const double face = triangleSolidAngle(a, b, c) + triangleSolidAngle(a, c, d);
        QVERIFY(std::abs(face - 4.0 * kPi / 6.0) < 1e-14);
        // Seen from outside (the eye in front of the face) the sign flips.
        const glm::dvec3 eye(0, 0, 3);
        const double outside = triangleSolidAngle(a - eye, b - eye, c - eye) +
                               triangleSolidAngle(a - eye, c - eye, d - eye);
        QVERIFY(outside < 0.0);
        // A square of side 2 at distance 2: 4·asin(1/5) (the rectangle formula).
        QVERIFY(std::abs(outside + 4.0 * std::asin(0.2)) < 1e-14);
    }

    void aTriangleIncidentToTheCentreHasNoSolidAngleWhateverTheRounding() {
        std::mt19937_64 rng(3);
        for (int i = 0; i < 500; ++i) {
            const glm::dmat3 m = randomRotation(rng);
            const glm::dvec3 x = randomPoint(rng, 100.0);
            const std::array<glm::dvec3, 3> p{x, x + m * glm::dvec3(0.7, 0.1, 0.0),
                                              x + m * glm::dvec3(0.2, 0.9, 0.0)};
            const double radius = i % 2 == 0 ? 0.5 : 2.0; // clipped, then wholly inside
            const Ball ball(x, radius);
            for (int corner = 0; corner < 3; ++corner) { // X as each vertex in turn
                const PreparedTriangle t =
                    prepareTriangle(p[corner], p[(corner + 1) % 3], p[(corner + 2) % 3]);
                const BallContribution c = ballContribution(t, ball);
                QCOMPARE(c.volume, 0.0);
                QCOMPARE(triangleSolidAngle(t.p0 - x, t.p1 - x, t.p2 - x), 0.0);
                if (radius > 1.0) {
                    QCOMPARE(c.area, t.area);
                }
            }
        }
        // Why h is forced to 0: a rounding-sized h puts a whole sector of solid angle in.
        const glm::dvec3 x(0.0);
        const PreparedTriangle t = prepareTriangle(x, {2, 0, 0}, {0, 2, 0});
        const Ball ball(x, 1.0);
        const BallPart exact = clippedPart(t, ball, 0.0);
        const BallPart rounded = clippedPart(t, ball, 1e-16);
        QCOMPARE(exact.area, kPi / 4.0);
        QCOMPARE(exact.solidAngle, 0.0);
        QVERIFY(std::abs(rounded.solidAngle - kPi / 2.0) < 1e-12);
    }

    void ballSumsAgreeWithTheSumOfSingleTriangles() {
        // Thousands of whole triangles in one ball: many readings of the batched product.
        std::mt19937_64 rng(17);
        const glm::dvec3 x(0.1, -0.2, 0.05);
        const Ball ball(x, 3.0);
        BallSums sums(ball);
        double area = 0.0, volume = 0.0;
        for (int i = 0; i < 5000; ++i) {
            const glm::dvec3 c = randomPoint(rng, 3.0);
            const PreparedTriangle t =
                prepareTriangle(c + 0.2 * randomPoint(rng, 1.0), c + 0.2 * randomPoint(rng, 1.0),
                                c + 0.2 * randomPoint(rng, 1.0));
            const BallContribution one = ballContribution(t, ball);
            QCOMPARE(int(sums.add(t)), int(one.path));
            area += one.area, volume += one.volume;
        }
        QVERIFY(std::abs(sums.area() - area) <= 1e-13 * area);
        QVERIFY2(
            std::abs(sums.volume(0.0) - volume) <= 1e-12 * ball.coneFactor,
            qPrintable(
                QString("%1 vs %2").arg(sums.volume(0.0), 0, 'g', 17).arg(volume, 0, 'g', 17)));
    }

    void aDegenerateTriangleAddsNothing() {
        const Ball ball(glm::dvec3(0.5, 0.0, 0.0), 2.0);
        const PreparedTriangle t = prepareTriangle({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
        QCOMPARE(t.area, 0.0);
        const BallContribution c = ballContribution(t, ball);
        QCOMPARE(c.area, 0.0);
        QCOMPARE(c.volume, 0.0);
        QCOMPARE(triangleSolidAngle(glm::dvec3(-0.5, 0, 0), glm::dvec3(0.5, 0, 0),
                                    glm::dvec3(1.5, 0, 0)),
                 0.0);
    }

    void contributionsAddUpOverASubdividedTriangle() {
        std::mt19937_64 rng(5);
        for (int i = 0; i < 500; ++i) {
            const std::array<glm::dvec3, 3> p{randomPoint(rng, 2.0), randomPoint(rng, 2.0),
                                              randomPoint(rng, 2.0)};
            const Ball ball(randomPoint(rng, 1.0), 1.5);
            const BallContribution whole =
                ballContribution(prepareTriangle(p[0], p[1], p[2]), ball);
            const glm::dvec3 m01 = 0.5 * (p[0] + p[1]), m12 = 0.5 * (p[1] + p[2]),
                             m20 = 0.5 * (p[2] + p[0]);
            double area = 0.0, volume = 0.0;
            for (const auto& q : {std::array{p[0], m01, m20}, std::array{p[1], m12, m01},
                                  std::array{p[2], m20, m12}, std::array{m01, m12, m20}}) {
                const BallContribution c =
                    ballContribution(prepareTriangle(q[0], q[1], q[2]), ball);
                area += c.area, volume += c.volume;
            }
            QVERIFY(std::abs(area - whole.area) < 1e-12);
            QVERIFY(std::abs(volume - whole.volume) < 1e-12);
        }
    }

    void theGridListsEveryTriangleThatMeetsTheBallOnce() {
        std::mt19937_64 rng(13);
        std::vector<PreparedTriangle> soup;
        glm::dvec3 lo(1e300), hi(-1e300);
        for (int i = 0; i < 3000; ++i) {
            const glm::dvec3 c = randomPoint(rng, 10.0);
            const PreparedTriangle t = prepareTriangle(
                c + randomPoint(rng, 1.0), c + randomPoint(rng, 1.0), c + randomPoint(rng, 1.0));
            soup.push_back(t);
            lo = glm::min(lo, glm::min(t.p0, glm::min(t.p1, t.p2)));
            hi = glm::max(hi, glm::max(t.p0, glm::max(t.p1, t.p2)));
        }
        for (const double cellOverRadius : {1.0, 0.5, 0.3}) {
            const double radius = 1.7;
            const TriangleGrid grid(GridFrame(lo, hi, cellOverRadius * radius, 1 << 20), soup);
            QueryStamps stamps(soup.size());
            for (int q = 0; q < 300; ++q) {
                const Ball ball(randomPoint(rng, 13.0), radius); // some outside the grid
                std::vector<int> visits(soup.size(), 0);
                grid.forEachCandidate(ball.centre, radius, stamps,
                                      [&](std::uint32_t id) { ++visits[id]; });
                for (std::size_t id = 0; id < soup.size(); ++id) {
                    QVERIFY(visits[id] <= 1);
                    if (ballContribution(soup[id], ball).area > 0.0) {
                        QVERIFY2(visits[id] == 1,
                                 qPrintable(QString("triangle %1 missed").arg(id)));
                    }
                }
            }
        }
    }

    void aGridTooFineForItsCellCapIsCoarsened() {
        const GridFrame frame(glm::dvec3(0.0), glm::dvec3(100.0), 0.01, 10000);
        QVERIFY(frame.cellCount() <= 10000);
        QVERIFY(frame.cellSize() > 0.01);
        QVERIFY(frame.cellCount() > 10000 / 3); // one step of 2^(1/3) too far at most
    }
};

QTEST_GUILESS_MAIN(TestSphereIntegrals)
#include "test_sphere_integrals.moc"
