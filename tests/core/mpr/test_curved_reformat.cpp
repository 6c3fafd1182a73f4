// Curved reformation on a synthetic curved tube of known radius: a half ring
// of 20 mm radius, 3 mm tube radius, clicked as 7 points. Straightened (at two
// turns) and stretched, the tube keeps a constant width of 2R along its whole
// length; lengths along the path are true; the cross-section is a disc of
// radius R; a slab shows what lies beside the cut.
#include <QTest>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/mpr/CurvedReformat.h"

using namespace lucent;

namespace {

constexpr double kRing = 20.0; // mm, radius of the ring the tube follows
constexpr double kTube = 3.0;  // mm, the tube's radius
const glm::dvec3 kCentre{30.0, 30.0, 15.0};

// Distance from the ring through the tube's axis.
double ringDistance(const glm::dvec3& p) {
    const glm::dvec3 d = p - kCentre;
    return std::hypot(std::hypot(d.x, d.y) - kRing, d.z);
}

// 1000 inside the tube, 0 outside, a 1 mm linear ramp at the wall (value 500
// exactly at radius kTube), so interpolation finds the wall to well under a voxel.
Volume tubeVolume(const glm::dvec3& bead = glm::dvec3(-100.0)) {
    VolumeGeometry g;
    g.dims = {120, 120, 60};
    g.spacing = {0.5, 0.5, 0.5};
    Volume v(g, VoxelType::Float32);
    auto out = v.voxels<float>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const glm::dvec3 p = g.toPatient(glm::dvec3(i, j, k));
                const double wall = std::clamp(0.5 - (ringDistance(p) - kTube), 0.0, 1.0);
                const double spot = glm::distance(p, bead) <= 1.0 ? 3000.0 : 0.0;
                out[v.linearIndex(i, j, k)] = float(std::max(1000.0 * wall, spot));
            }
        }
    }
    return v;
}

std::vector<glm::dvec3> clickedHalfRing() {
    std::vector<glm::dvec3> points;
    for (int k = 0; k <= 6; ++k) {
        const double a = std::numbers::pi * k / 6.0;
        points.push_back(kCentre + kRing * glm::dvec3(std::cos(a), std::sin(a), 0.0));
    }
    return points;
}

// Where a row crosses 500 on each side of the path: the tube's width in pixels.
double widthOfRow(const CurvedImage& image, int y) {
    const int centre = int(std::lround(image.pathColumn[y]));
    const auto at = [&](int x) { return double(image.pixels[std::size_t(y) * image.width + x]); };
    const auto edge = [&](int dir) {
        for (int x = centre; x + dir >= 0 && x + dir < image.width; x += dir) {
            if (at(x + dir) < 500.0) {
                return x + dir * (at(x) - 500.0) / (at(x) - at(x + dir));
            }
        }
        return std::numeric_limits<double>::quiet_NaN(); // no wall: the check fails
    };
    return edge(+1) - edge(-1);
}

void verifyConstantWidth(const CurvedImage& image, const char* what) {
    double low = 1e9, high = 0.0;
    // Leave out the first and last 2 mm, where the tube's end caps of the spline sit.
    const int margin = int(2.0 / image.pixelSize);
    for (int y = margin; y < image.height - margin; ++y) {
        const double w = widthOfRow(image, y);
        low = std::min(low, w);
        high = std::max(high, w);
    }
    const double expected = 2.0 * kTube / image.pixelSize;
    QVERIFY2(high - low <= 1.0,
             qPrintable(QString("%1: width %2..%3 px").arg(what).arg(low).arg(high)));
    QVERIFY2(std::abs(low - expected) <= 1.0 && std::abs(high - expected) <= 1.0,
             qPrintable(QString("%1: width %2..%3 px, expected %4")
                            .arg(what)
                            .arg(low)
                            .arg(high)
                            .arg(expected)));
}

} // namespace

class TestCurvedReformat : public QObject {
    Q_OBJECT
private slots:
    void centerlineFollowsTheClickedRing() {
        const Centerline c = centerlineThrough(clickedHalfRing(), 0.25);
        // Half the circumference, within the spline's error between clicks.
        QVERIFY(std::abs(c.length() - std::numbers::pi * kRing) < 0.2);
        // Between the inner clicks the spline holds the ring closely; in the two
        // end pieces, which have no click beyond them, it runs straighter.
        double worst = 0.0, worstEnd = 0.0;
        const double piece = std::numbers::pi * kRing / 6.0;
        for (std::size_t i = 0; i < c.points.size(); ++i) {
            const double s = double(i) * c.step;
            const bool end = s < piece || s > c.length() - piece;
            (end ? worstEnd : worst) = std::max(end ? worstEnd : worst, ringDistance(c.points[i]));
            QVERIFY(std::abs(glm::dot(c.normals[i], c.tangents[i])) < 1e-9);
        }
        qInfo("spline off the ring by at most %.3f mm (end pieces %.3f); length %.3f of %.3f mm",
              worst, worstEnd, c.length(), std::numbers::pi * kRing);
        QVERIFY(worst < 0.1);
        QVERIFY(worstEnd < 0.5);
        // The path lies in one plane: the frame carried without twist keeps
        // its normal along +z (up) all the way.
        QVERIFY(glm::distance(c.normals.back(), glm::dvec3(0, 0, 1)) < 1e-6);
    }

    void straightenedTubeHasConstantWidth() {
        const Volume v = tubeVolume();
        const Centerline c = centerlineThrough(clickedHalfRing(), 0.25);
        CurvedOptions o;
        o.pixelSize = 0.25;
        o.halfWidth = 8.0;
        for (const double turn : {0.0, 90.0, 35.0}) {
            o.rotationDeg = turn;
            const CurvedImage image = straightenedReformat(v, c, o);
            QCOMPARE(image.height, int(std::floor(c.length() / 0.25)) + 1);
            verifyConstantWidth(image,
                                qPrintable(QString("straightened, turned %1 deg").arg(turn)));
        }
    }

    void stretchedTubeHasConstantWidthAndTrueLength() {
        const Volume v = tubeVolume();
        const Centerline c = centerlineThrough(clickedHalfRing(), 0.25);
        CurvedOptions o;
        o.pixelSize = 0.25;
        o.halfWidth = 8.0;
        // Up across the ring's plane: the cut runs lengthwise through the tube.
        const CurvedImage image = stretchedReformat(v, c, {0.0, 0.0, 1.0}, o);
        verifyConstantWidth(image, "stretched");
        // The path seen along up is the ring itself: rows cover its true length.
        QVERIFY(std::abs((image.height - 1) * o.pixelSize - c.length()) <= o.pixelSize);
        QVERIFY(std::abs(image.rowArc.back() - c.length()) <= o.pixelSize);
        for (const double col : image.pathColumn) {
            QVERIFY(std::abs(col - 8.0 / 0.25) < 1e-6);
        }
        // Every pixel's patient point is on the swept surface (the ring's cylinder).
        const glm::dvec3 p = image.pointAt(10.0, image.height / 2);
        QVERIFY(std::abs(std::hypot(p.x - kCentre.x, p.y - kCentre.y) - kRing) < 0.15);
    }

    void crossSectionIsADiscOfTheTubeRadius() {
        const Volume v = tubeVolume();
        const Centerline c = centerlineThrough(clickedHalfRing(), 0.25);
        for (const double s : {10.0, c.length() / 2, 50.0}) {
            const SlicePlane plane = crossSection(c, s, 64, 0.2);
            QVERIFY(std::abs(std::abs(glm::dot(plane.normal(), c.tangentAt(s))) - 1.0) < 1e-9);
            const std::vector<float> pixels = sampleImage(v, plane);
            double area = 0.0;
            for (const float p : pixels) {
                area += std::clamp(double(p) / 1000.0, 0.0, 1.0) * 0.2 * 0.2;
            }
            const double disc = std::numbers::pi * kTube * kTube;
            QVERIFY2(
                std::abs(area - disc) < 0.05 * disc,
                qPrintable(QString("area %1 mm2 at s=%2, disc %3").arg(area).arg(s).arg(disc)));
        }
    }

    void slabShowsWhatLiesBesideTheCut() {
        // A bead 2.5 mm above the ring's plane, over the path's midpoint. Unturned,
        // the cut holds +z (the first normal, from up): the bead is in it. Turned
        // 90 degrees the cut is the ring's plane and +z runs across it, the
        // slab's direction: a thin cut misses the bead, an 8 mm slab reaches it.
        const double a = std::numbers::pi / 2;
        const glm::dvec3 bead =
            kCentre + kRing * glm::dvec3(std::cos(a), std::sin(a), 0.0) + glm::dvec3(0, 0, 2.5);
        const Volume v = tubeVolume(bead);
        const Centerline c = centerlineThrough(clickedHalfRing(), 0.25);
        const auto brightest = [&](const CurvedOptions& o) {
            const CurvedImage image = straightenedReformat(v, c, o);
            float best = 0.0F;
            for (const float p : image.pixels) {
                best = std::isnan(p) ? best : std::max(best, p);
            }
            return best;
        };
        CurvedOptions o;
        o.pixelSize = 0.25;
        o.halfWidth = 8.0;
        QVERIFY(brightest(o) > 2000.0F);
        o.rotationDeg = 90.0;
        QVERIFY(brightest(o) <= 1000.0F);
        o.slabThickness = 8.0;
        QVERIFY(brightest(o) > 2000.0F);
        o.slabMode = SlabMode::MinIp;
        QVERIFY(brightest(o) <= 1000.0F);
    }

    void badPathsAreRefused() {
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 centerlineThrough({{1, 2, 3}, {1, 2, 3}}, 0.5));
        const Volume v = tubeVolume();
        const Centerline vertical = centerlineThrough({{30, 30, 5}, {30, 30, 25}}, 0.5);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 stretchedReformat(v, vertical, {0, 0, 1}, CurvedOptions{}));
    }
};

QTEST_APPLESS_MAIN(TestCurvedReformat)
#include "test_curved_reformat.moc"
