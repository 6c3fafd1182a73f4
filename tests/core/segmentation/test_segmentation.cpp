// Segmentation on the real 28-slice CT (0.7 x 0.7 x 5 mm voxels): each effect against a
// reference the test computes its own way (a plain loop, union-find islands, brute-force
// Euclidean distances and diameters), the statistics against a hand computation, the undo
// history.
#include <QTest>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>

#include <glm/vector_relational.hpp>

#include "core/io/Catalog.h"
#include "core/segmentation/SegmentEffects.h"
#include "core/segmentation/SegmentStatistics.h"
#include "core/segmentation/Segmentation.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";

// Union-find over face neighbours: each voxel's island root.
struct Islands {
    std::vector<std::size_t> parent;
    std::size_t root(std::size_t i) {
        while (parent[i] != i) {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        return i;
    }
    explicit Islands(const SegmentMask& m) : parent(m.size()) {
        std::iota(parent.begin(), parent.end(), std::size_t{0});
        const glm::ivec3 d = m.dims();
        for (int k = 0; k < d.z; ++k) {
            for (int j = 0; j < d.y; ++j) {
                for (int i = 0; i < d.x; ++i) {
                    if (!m.at(i, j, k)) {
                        continue;
                    }
                    const std::size_t a = m.linearIndex(i, j, k);
                    if (i > 0 && m.at(i - 1, j, k)) {
                        parent[root(a)] = root(m.linearIndex(i - 1, j, k));
                    }
                    if (j > 0 && m.at(i, j - 1, k)) {
                        parent[root(a)] = root(m.linearIndex(i, j - 1, k));
                    }
                    if (k > 0 && m.at(i, j, k - 1)) {
                        parent[root(a)] = root(m.linearIndex(i, j, k - 1));
                    }
                }
            }
        }
    }
};

std::vector<glm::ivec3> setVoxels(const SegmentMask& m) {
    std::vector<glm::ivec3> out;
    m.forEachSet([&](std::size_t i) { out.push_back(m.voxelOf(i)); });
    return out;
}

} // namespace

class TestSegmentation : public QObject {
    Q_OBJECT

    Volume ct_;

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        ct_ = loadPath(test::kRealData / kCt);
        QCOMPARE(ct_.dims(), glm::ivec3(512, 512, 28));
    }

    void thresholdIsEveryVoxelInRange() {
        const SegmentMask bone = thresholdMask(ct_, 300.0, 3000.0);
        std::size_t expected = 0;
        for (int k = 0; k < 28; ++k) {
            for (int j = 0; j < 512; ++j) {
                for (int i = 0; i < 512; ++i) {
                    const double v = ct_.value(i, j, k);
                    const bool in = v >= 300.0 && v <= 3000.0;
                    expected += in;
                    if (in != bone.at(i, j, k)) {
                        QFAIL(qPrintable(QString("voxel %1 %2 %3").arg(i).arg(j).arg(k)));
                    }
                }
            }
        }
        QCOMPARE(bone.count(), expected);
        QVERIFY(expected > 10000);
    }

    void islandsMatchUnionFind() {
        const SegmentMask bone = thresholdMask(ct_, 300.0, 3000.0);
        Islands reference(bone);
        std::map<std::size_t, std::size_t> sizes;
        bone.forEachSet([&](std::size_t i) { ++sizes[reference.root(i)]; });
        const std::vector<Island> islands = islandsOf(bone);
        QCOMPARE(islands.size(), sizes.size());
        QVERIFY(islands.size() > 3);
        const auto largest = std::max_element(sizes.begin(), sizes.end(),
                                              [](auto& a, auto& b) { return a.second < b.second; });
        QCOMPARE(islands.front().voxels, largest->second);
        // Keep largest: exactly the voxels of that root.
        const SegmentMask kept = keepLargestIsland(bone);
        QCOMPARE(kept.count(), largest->second);
        bone.forEachSet(
            [&](std::size_t i) { QCOMPARE(kept.get(i), reference.root(i) == largest->first); });
        // Remove under 50 mm^3: islands of fewer than 50 / (0.7 x 0.7 x 5) voxels go.
        const VolumeGeometry& g = ct_.geometry();
        const double voxelMm3 = g.spacing.x * g.spacing.y * g.spacing.z;
        const SegmentMask big = removeSmallIslands(bone, g, 50.0);
        bone.forEachSet([&](std::size_t i) {
            QCOMPARE(big.get(i), double(sizes[reference.root(i)]) * voxelMm3 >= 50.0);
        });
        // The island clicked.
        const glm::ivec3 seed = bone.voxelOf(islands[1].first);
        const SegmentMask one = keepIslandAt(bone, seed);
        QCOMPARE(one.count(), islands[1].voxels);
        QVERIFY(!keepIslandAt(bone, {0, 0, 0}).any());
    }

    void marginIsTheExactEuclideanDistance() {
        // Bone in a block of the CT around one of its voxels, so brute force stays quick;
        // spacing 0.7 x 0.7 x 5 mm.
        const SegmentMask bone = thresholdMask(ct_, 400.0, 3000.0);
        const std::vector<glm::ivec3> all = setVoxels(bone);
        QVERIFY(!all.empty());
        const glm::ivec3 c =
            glm::clamp(all[all.size() / 2], glm::ivec3(60, 60, 6), glm::ivec3(451, 451, 21));
        const glm::ivec3 lo = c - glm::ivec3(12, 12, 3), hi = c + glm::ivec3(12, 12, 3);
        SegmentMask block(bone.dims());
        for (const glm::ivec3& v : all) {
            if (glm::all(glm::greaterThanEqual(v, lo)) && glm::all(glm::lessThan(v, hi))) {
                block.set(block.linearIndex(v.x, v.y, v.z));
            }
        }
        const std::vector<glm::ivec3> set = setVoxels(block);
        qInfo("%zu bone voxels in the block around %d %d %d", set.size(), c.x, c.y, c.z);
        QVERIFY(set.size() > 100);
        const VolumeGeometry& g = ct_.geometry();
        const auto mm2 = [&](const glm::ivec3& a, const glm::ivec3& b) {
            const glm::dvec3 d = glm::dvec3(a - b) * g.spacing;
            return glm::dot(d, d);
        };
        for (const double r : {2.1, 5.0, 7.3}) {
            const SegmentMask grown = marginMask(block, g, r);
            int checked = 0;
            for (int k = 0; k < 28; ++k) {
                for (int j = lo.y - 12; j < hi.y + 12; ++j) {
                    for (int i = lo.x - 12; i < hi.x + 12; ++i) {
                        double best = 1e300;
                        for (const glm::ivec3& s : set) {
                            best = std::min(best, mm2({i, j, k}, s));
                        }
                        QCOMPARE(grown.at(i, j, k), best <= r * r * (1.0 + 1e-9));
                        ++checked;
                    }
                }
            }
            QVERIFY(checked > 0);
            QVERIFY(grown.count() > block.count());
        }
        // Shrink by 1.5 mm: a voxel stays when every unset voxel is farther than 1.5 mm.
        const SegmentMask shrunk = marginMask(block, g, -1.5);
        std::vector<glm::ivec3> unset;
        for (int k = lo.z - 1; k <= hi.z; ++k) {
            for (int j = lo.y - 1; j <= hi.y; ++j) {
                for (int i = lo.x - 1; i <= hi.x; ++i) {
                    if (!block.at(i, j, k)) {
                        unset.push_back({i, j, k});
                    }
                }
            }
        }
        for (const glm::ivec3& s : set) {
            double best = 1e300;
            for (const glm::ivec3& u : unset) {
                best = std::min(best, mm2(s, u));
            }
            QCOMPARE(shrunk.at(s.x, s.y, s.z), best > 1.5 * 1.5 * (1.0 + 1e-9));
        }
        QVERIFY(shrunk.count() < block.count());
        // Hollow: the mask minus its shrink.
        SegmentMask shell = block;
        shell.subtract(shrunk);
        QCOMPARE(hollowMask(block, g, 1.5), shell);
    }

    void statisticsByHand() {
        const SegmentMask bone = keepLargestIsland(thresholdMask(ct_, 300.0, 3000.0));
        const SegmentStatistics s = segmentStatistics(bone, ct_);
        std::vector<double> values;
        bone.forEachSet([&](std::size_t i) {
            const glm::ivec3 v = bone.voxelOf(i);
            values.push_back(ct_.value(v.x, v.y, v.z));
        });
        const double n = double(values.size());
        const double mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
        double ss = 0.0;
        for (const double v : values) {
            ss += (v - mean) * (v - mean);
        }
        const VolumeGeometry& g = ct_.geometry();
        QCOMPARE(s.voxels, values.size());
        QVERIFY(std::abs(s.volumeMl - n * g.spacing.x * g.spacing.y * g.spacing.z / 1000.0) <
                1e-9 * s.volumeMl);
        QVERIFY(std::abs(s.mean - mean) < 1e-9 * std::abs(mean));
        QVERIFY(std::abs(s.standardDeviation - std::sqrt(ss / n)) < 1e-9 * s.standardDeviation);
        std::sort(values.begin(), values.end());
        QCOMPARE(s.minimum, values.front());
        QCOMPARE(s.maximum, values.back());
        QCOMPARE(s.median, values[(values.size() - 1) / 2]);
        QVERIFY(s.surfaceAreaCm2 > 0.0);
        qInfo("bone: %zu voxels, %.2f mL, mean %.1f HU, area %.1f cm2, diameter %.1f mm", s.voxels,
              s.volumeMl, s.mean, s.surfaceAreaCm2, s.largestDiameterMm);
        // The diameter against every pair of the island's voxels in a few slices.
        SegmentMask few(bone.dims());
        bone.forEachSet([&](std::size_t i) {
            if (bone.voxelOf(i).z % 9 == 4) {
                few.set(i);
            }
        });
        const std::vector<glm::ivec3> pts = setVoxels(few);
        double best = 0.0;
        for (std::size_t a = 0; a < pts.size(); a += 1) {
            for (std::size_t b = a + 1; b < pts.size(); ++b) {
                const glm::dvec3 d =
                    g.toPatient(glm::dvec3(pts[a])) - g.toPatient(glm::dvec3(pts[b]));
                best = std::max(best, glm::dot(d, d));
            }
        }
        QVERIFY(std::abs(largestDiameterMm(few, g) - std::sqrt(best)) < 1e-9);
        // An empty mask: nothing, no error.
        const SegmentStatistics none = segmentStatistics(SegmentMask(ct_.dims()), ct_);
        QCOMPARE(none.voxels, std::size_t{0});
        QVERIFY(std::isnan(none.mean));
    }

    void ballAreaAndDiameter() {
        // A ball of radius 20 mm on a 1 mm grid: 4 pi r^2 within 2 %, diameter 40 mm.
        VolumeGeometry g;
        g.dims = {61, 61, 61};
        Volume v(g, VoxelType::Int16);
        SegmentMask ball(g.dims);
        for (int k = 0; k < 61; ++k) {
            for (int j = 0; j < 61; ++j) {
                for (int i = 0; i < 61; ++i) {
                    if (glm::length(glm::dvec3(i - 30, j - 30, k - 30)) <= 20.0) {
                        ball.set(ball.linearIndex(i, j, k));
                    }
                }
            }
        }
        const SegmentStatistics s = segmentStatistics(ball, v);
        const double area = 4.0 * std::numbers::pi * 20.0 * 20.0 / 100.0;
        qInfo("ball area %.2f cm2 (sphere %.2f)", s.surfaceAreaCm2, area);
        QVERIFY(std::abs(s.surfaceAreaCm2 - area) < 0.02 * area);
        QCOMPARE(s.largestDiameterMm, 40.0);
    }

    void undoHistory() {
        Segmentation seg(ct_.geometry(), 3);
        const std::uint32_t bone = seg.add("Bone", findSegmentKind("bone"));
        QCOMPARE(seg.find(bone)->type.value, std::string("272673000"));
        QVERIFY(!seg.find(bone)->mask->any());
        const std::uint64_t before = seg.revision();
        QVERIFY(
            seg.setMask(bone, thresholdMask(ct_, 300.0, 3000.0), "Threshold", "Lucent threshold"));
        QVERIFY(seg.revision() > before);
        QCOMPARE(seg.find(bone)->algorithmType, std::string("SEMIAUTOMATIC"));
        const std::size_t thresholded = seg.find(bone)->mask->count();
        QVERIFY(seg.setMask(bone, keepLargestIsland(*seg.find(bone)->mask), "Keep largest island"));
        QVERIFY(seg.find(bone)->mask->count() < thresholded);
        seg.setVisible(bone, false);
        QCOMPARE(seg.undoText(), std::string("Keep largest island"));
        QVERIFY(seg.undo());
        QCOMPARE(seg.find(bone)->mask->count(), thresholded);
        QVERIFY(!seg.find(bone)->visible); // not an edit: stays as it is
        QVERIFY(seg.redo());
        QVERIFY(seg.find(bone)->mask->count() < thresholded);
        // Locked: effects leave it alone.
        seg.setLocked(bone, true);
        QVERIFY(!seg.setMask(bone, SegmentMask(ct_.dims()), "Clear"));
        QVERIFY(seg.find(bone)->mask->any());
        // The history keeps 3 steps.
        seg.setLocked(bone, false);
        seg.rename(bone, "Skeleton");
        seg.add("Table", findSegmentKind("table"));
        int undone = 0;
        while (seg.undo()) {
            ++undone;
        }
        QCOMPARE(undone, 3);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 seg.setMask(bone, SegmentMask({2, 2, 2}), "Wrong grid"));
    }
};

QTEST_GUILESS_MAIN(TestSegmentation)
#include "test_segmentation.moc"
