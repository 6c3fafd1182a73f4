// The k-d split of a volume's bricks among parts: the boxes tile the volume,
// the weight is balanced by visible bricks, and the front-to-back order agrees
// with the order in which rays from the eye meet the boxes.
#include <QTest>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

#include "core/volume/VolumePartition.h"

using namespace lucent;

namespace {

// A table of bricks whose values are 1000 where `visible` says and 0 elsewhere.
BrickTable table(glm::ivec3 dims, int brickSize, const std::function<bool(glm::ivec3)>& visible) {
    BrickTable t;
    t.dims = dims;
    t.brickSize = brickSize;
    t.perAxis = (dims + brickSize - 1) / brickSize;
    for (int k = 0; k < t.perAxis.z; ++k) {
        for (int j = 0; j < t.perAxis.y; ++j) {
            for (int i = 0; i < t.perAxis.x; ++i) {
                const float v = visible({i, j, k}) ? 1000.0f : 0.0f;
                t.range.emplace_back(0.0f, v);
            }
        }
    }
    return t;
}

bool aboveHalf(double, double hi) {
    return hi > 500.0;
}

// Whether the voxel-centre position p lies in the box (half-open, closed at dims - 1).
bool inBox(const PartBox& b, glm::dvec3 p, glm::ivec3 dims) {
    for (int a = 0; a < 3; ++a) {
        const bool closedHi = b.hi[a] == dims[a] - 1;
        if (p[a] < b.lo[a] || p[a] > b.hi[a] || (!closedHi && p[a] == double(b.hi[a]))) {
            return false;
        }
    }
    return true;
}

} // namespace

class TestVolumePartition : public QObject {
    Q_OBJECT

private slots:
    void boxesTileTheVolume_data() {
        QTest::addColumn<int>("parts");
        for (int n : {1, 2, 3, 4, 5, 7, 8}) {
            QTest::newRow(qPrintable(QString::number(n))) << n;
        }
    }
    void boxesTileTheVolume() {
        QFETCH(int, parts);
        const glm::ivec3 dims(70, 45, 33);
        const BrickTable t = table(dims, 16, [](glm::ivec3 b) { return b.x + b.y > 3; });
        const VolumePartition p(t, glm::dvec3(0.7, 0.7, 2.0), parts, aboveHalf);
        QCOMPARE(p.parts(), parts);
        // Every voxel centre and every half-voxel position lies in exactly one box.
        for (double z = 0; z <= dims.z - 1; z += 0.5) {
            for (double y = 0; y <= dims.y - 1; y += 0.5) {
                for (double x = 0; x <= dims.x - 1; x += 0.5) {
                    int owners = 0;
                    for (int n = 0; n < parts; ++n) {
                        owners += inBox(p.box(n), {x, y, z}, dims) ? 1 : 0;
                    }
                    if (owners != 1) {
                        QFAIL(qPrintable(QString("(%1, %2, %3) lies in %4 boxes")
                                             .arg(x)
                                             .arg(y)
                                             .arg(z)
                                             .arg(owners)));
                    }
                }
            }
        }
        // Cuts lie on brick boundaries.
        for (int n = 0; n < parts; ++n) {
            for (int a = 0; a < 3; ++a) {
                QCOMPARE(p.box(n).lo[a] % 16, 0);
                QVERIFY(p.box(n).hi[a] == dims[a] - 1 || p.box(n).hi[a] % 16 == 0);
            }
        }
    }

    void balancesVisibleBricksNotVoxels() {
        // Only the first third of the bricks along x shows: halving the volume
        // would give one part all the work.
        const glm::ivec3 dims(192, 64, 64);
        const BrickTable t = table(dims, 16, [](glm::ivec3 b) { return b.x < 4; });
        for (int parts : {2, 3, 4}) {
            const VolumePartition p(t, glm::dvec3(1.0), parts, aboveHalf);
            double lo = 1e300, hi = 0.0, total = 0.0;
            for (int n = 0; n < parts; ++n) {
                lo = std::min(lo, p.weight(n));
                hi = std::max(hi, p.weight(n));
                total += p.weight(n);
            }
            const double mean = total / parts;
            QVERIFY2(
                hi <= 1.25 * mean,
                qPrintable(QString("%1 parts: heaviest %2, mean %3").arg(parts).arg(hi).arg(mean)));
            // The visible bricks are split, not the volume: no part is nearly idle.
            QVERIFY2(
                lo >= 0.75 * mean,
                qPrintable(QString("%1 parts: lightest %2, mean %3").arg(parts).arg(lo).arg(mean)));
        }
    }

    void frontToBackMatchesRays() {
        const glm::ivec3 dims(90, 70, 50);
        const BrickTable t =
            table(dims, 16, [](glm::ivec3 b) { return (b.x + 2 * b.y + b.z) % 3 != 0; });
        std::mt19937 random(7);
        std::uniform_real_distribution<double> unit(-1.0, 1.0);
        for (int parts : {2, 3, 4, 6}) {
            const VolumePartition p(t, glm::dvec3(1.0), parts, aboveHalf);
            for (int trial = 0; trial < 40; ++trial) {
                // Eyes outside the volume and inside it.
                const glm::dvec3 eye =
                    glm::dvec3(dims) * 0.5 + glm::dvec3(unit(random), unit(random), unit(random)) *
                                                 (trial % 4 == 0 ? 30.0 : 200.0);
                const std::vector<int> order = p.frontToBack(eye);
                QCOMPARE(int(order.size()), parts);
                std::vector<int> rankOf(std::size_t(parts), -1);
                for (int i = 0; i < parts; ++i) {
                    rankOf[std::size_t(order[std::size_t(i)])] = i;
                }
                QVERIFY(std::find(rankOf.begin(), rankOf.end(), -1) == rankOf.end());
                for (int ray = 0; ray < 200; ++ray) {
                    const glm::dvec3 target(std::abs(unit(random)) * (dims.x - 1),
                                            std::abs(unit(random)) * (dims.y - 1),
                                            std::abs(unit(random)) * (dims.z - 1));
                    const glm::dvec3 d = target - eye;
                    // Boxes in the order the ray enters them (slab test).
                    std::vector<std::pair<double, int>> hits;
                    for (int n = 0; n < parts; ++n) {
                        double t0 = 0.0, t1 = 1e300;
                        for (int a = 0; a < 3; ++a) {
                            const double lo = p.box(n).lo[a], hi = p.box(n).hi[a];
                            if (std::abs(d[a]) < 1e-12) {
                                if (eye[a] < lo || eye[a] > hi) {
                                    t1 = -1.0;
                                }
                                continue;
                            }
                            const double ta = (lo - eye[a]) / d[a], tb = (hi - eye[a]) / d[a];
                            t0 = std::max(t0, std::min(ta, tb));
                            t1 = std::min(t1, std::max(ta, tb));
                        }
                        if (t1 > t0 + 1e-9) {
                            hits.emplace_back(t0, n);
                        }
                    }
                    std::sort(hits.begin(), hits.end());
                    for (std::size_t h = 1; h < hits.size(); ++h) {
                        QVERIFY2(rankOf[std::size_t(hits[h - 1].second)] <
                                     rankOf[std::size_t(hits[h].second)],
                                 "a ray meets a box before one the order puts in front of it");
                    }
                }
            }
        }
    }

    void aPreferredAxisIsCutWhenItBalances() {
        // A volume long in x: unpreferred, the cuts go across x; preferring k
        // (DICOM slabs), across k, as long as k has bricks enough.
        const BrickTable t = table({256, 128, 128}, 16, [](glm::ivec3) { return true; });
        const VolumePartition free(t, glm::dvec3(1.0), 4, aboveHalf);
        const VolumePartition slabs(t, glm::dvec3(1.0), 4, aboveHalf, 2);
        for (int n = 0; n < 4; ++n) {
            QCOMPARE(slabs.box(n).lo.x, 0);
            QCOMPARE(slabs.box(n).hi.x, 255);
            QCOMPARE(slabs.box(n).lo.y, 0);
            QCOMPARE(slabs.box(n).hi.y, 127);
        }
        QVERIFY(free.box(0).hi.x < 255 || free.box(1).hi.x < 255);
    }

    void moreRanksThanBricksIsAClearError() {
        const BrickTable t = table({40, 20, 20}, 16, [](glm::ivec3) { return true; });
        // 3 x 2 x 2 = 12 bricks.
        QVERIFY_THROWS_NO_EXCEPTION(VolumePartition(t, glm::dvec3(1.0), 12, aboveHalf));
        try {
            const VolumePartition p(t, glm::dvec3(1.0), 13, aboveHalf);
            QFAIL("13 parts of 12 bricks were accepted");
        } catch (const std::invalid_argument& e) {
            const QString what = e.what();
            QVERIFY2(what.contains("13") && what.contains("12 bricks"), qPrintable(what));
        }
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 VolumePartition(t, glm::dvec3(1.0), 0, aboveHalf));
    }

    void onePartIsTheWholeVolume() {
        const BrickTable t = table({40, 20, 20}, 16, [](glm::ivec3) { return false; });
        const VolumePartition p(t, glm::dvec3(1.0), 1, aboveHalf);
        QCOMPARE(p.box(0), (PartBox{glm::ivec3(0), glm::ivec3(39, 19, 19)}));
        QCOMPARE(p.frontToBack(glm::dvec3(-5.0)), std::vector<int>{0});
    }

    void partVoxelsHoldTheBoxAndItsHalo() {
        const PartBox box{{16, 0, 32}, {32, 19, 48}};
        const auto [first, last] = partVoxels(box, {64, 20, 60}, 3);
        QCOMPARE(first, glm::ivec3(13, 0, 29));
        QCOMPARE(last, glm::ivec3(36, 20, 52));
    }
};

QTEST_APPLESS_MAIN(TestVolumePartition)
#include "test_volume_partition.moc"
