// The GPU's residency decisions, tested without GL: LOD levels, which bricks a
// budget takes, slot reuse, and the voxels a slot holds.
#include <QTest>

#include "core/volume/BrickResidency.h"
#include "core/volume/LodPyramid.h"
#include "tests/core/raycast/RaycastScenes.h"

using namespace lucent;
using namespace lucent::test;

class TestBrickResidency : public QObject {
    Q_OBJECT

private slots:
    void downsamplingAveragesAndPlacesVoxels() {
        Volume v = makeVolume(
            {5, 4, 3}, [](int i, int j, int k) { return i + 10 * j + 100 * k; }, VoxelType::Int16);
        VolumeGeometry g = v.geometry();
        g.spacing = {0.5, 0.5, 2.0};
        g.origin = {10, 20, 30};
        v.setGeometry(g);
        const Volume h = downsampleByTwo(v);
        QCOMPARE(h.dims(), glm::ivec3(3, 2, 2));
        QCOMPARE(h.geometry().spacing, glm::dvec3(1.0, 1.0, 4.0));
        QCOMPARE(h.geometry().origin, glm::dvec3(10.25, 20.25, 31.0));
        // (0,0,0) averages i 0-1, j 0-1, k 0-1: 0.5 + 5 + 50 = 55.5, rounded half away.
        QCOMPARE(h.value(0, 0, 0), 56.0);
        // The lone last column i = 4 and the lone last slice k = 2.
        QCOMPARE(h.value(2, 0, 1), 4.0 + 5.0 + 200.0);
        QCOMPARE(h.modality, v.modality);
    }

    void pyramidStopsAtTheSmallestSize() {
        const Volume v = makeVolume({100, 40, 9}, [](int, int, int) { return 1.0; });
        const LodPyramid p(v, 16);
        QCOMPARE(p.levelCount(), 4); // 100 -> 50 -> 25 -> 13
        QCOMPARE(p.level(3).dims(), glm::ivec3(13, 5, 2));
        QCOMPARE(&p.level(0), &v);
        QVERIFY_THROWS_EXCEPTION(std::out_of_range, p.level(4));
        const glm::dvec3 p0(7.25, 3.0, 1.5);
        const glm::dvec3 back = LodPyramid::toLevel0(LodPyramid::fromLevel0(p0, 2), 2);
        QVERIFY(glm::length(back - p0) < 1e-12);
        QCOMPARE(LodPyramid::fromLevel0(glm::dvec3(0.5), 1), glm::dvec3(0.0));
    }

    // Only visible bricks are planned; the finest level that fits wins; the
    // neighbours shell is added when asked for; too small a pool says so.
    void planTakesTheFinestLevelThatFits() {
        const Volume v =
            makeVolume({64, 64, 64}, [](int i, int, int) { return i < 20 ? 100.0 : 0.0; });
        const LodPyramid pyramid(v, 8);
        std::vector<BrickGrid> grids;
        for (int n = 0; n < pyramid.levelCount(); ++n) {
            grids.emplace_back(pyramid.level(n), 16, 3);
        }
        std::vector<const BrickGrid*> levels;
        for (const BrickGrid& g : grids) {
            levels.push_back(&g);
        }
        const auto visible = [](double, double hi) { return hi > 50.0; };
        // Level 0: 4^3 bricks of 16; those with i < 20 + overlap: the first two columns.
        const ResidencyPlan fine = planResidency(levels, visible, ClipBox{}, false, 1000);
        QCOMPARE(fine.level, 0);
        QCOMPARE(fine.bricks.size(), std::size_t(2 * 16));
        QCOMPARE(fine.needed, fine.bricks.size());
        QVERIFY(fine.rejected.empty());
        const ResidencyPlan coarse = planResidency(levels, visible, ClipBox{}, false, 10);
        QCOMPARE(coarse.level, 1);
        QCOMPARE(coarse.rejected, std::vector<std::size_t>{32});
        QVERIFY(coarse.bricks.size() <= 10);
        const ResidencyPlan shell = planResidency(levels, visible, ClipBox{}, true, 1000);
        QCOMPARE(shell.needed, std::size_t(32));
        QCOMPARE(shell.bricks.size(), std::size_t(48)); // one more column, leapt over
        QCOMPARE(std::count(shell.leapable.begin(), shell.leapable.end(), 1), 16);
        // Only boxes left of i = 24 in view: the first column of bricks (its core ends at 16).
        const BoxTest leftOnly = [](const glm::dvec3& lo, const glm::dvec3&) { return lo.x < 8.0; };
        const ResidencyPlan seen = planResidency(levels, visible, ClipBox{}, false, 1000, leftOnly);
        QCOMPARE(seen.needed, std::size_t(16));
        ClipBox clip;
        clip.lo = {40, 0, 0}; // nothing visible right of i = 40
        QCOMPARE(planResidency(levels, visible, clip, false, 1000).needed, std::size_t(0));
        try {
            planResidency(
                levels, [](double, double) { return true; }, ClipBox{}, false, 0);
            QFAIL("an empty pool took a plan");
        } catch (const BudgetError& e) {
            QVERIFY2(std::string(e.what()).find("holds 0 bricks") != std::string::npos, e.what());
        }
    }

    void slotsAreReusedLeastRecentlyUsedFirst() {
        BrickSlots pool(3);
        const auto a = BrickSlots::key(0, 1), b = BrickSlots::key(0, 2), c = BrickSlots::key(0, 3),
                   d = BrickSlots::key(1, 1);
        QCOMPARE(pool.acquire({a, b}).size(), std::size_t(2));
        QCOMPARE(pool.acquire({a, b}).size(), std::size_t(0)); // resident: nothing to upload
        QCOMPARE(pool.acquire({c}).size(), std::size_t(1));
        // d needs a slot: a and b were used before c, a and b equally: one of them goes.
        pool.acquire({a, c});
        const auto up = pool.acquire({d, c});
        QCOMPARE(up.size(), std::size_t(1));
        QCOMPARE(up[0].slot, *pool.slotOf(d));
        QVERIFY(!pool.slotOf(b)); // b was the least recently used
        QVERIFY(pool.slotOf(a) && pool.slotOf(c));
        QCOMPARE(pool.resident(), std::size_t(3));
        QVERIFY_THROWS_EXCEPTION(std::length_error, pool.acquire({a, b, c, d}));
    }

    void slotHoldsTheBrickAndItsBorder() {
        const glm::ivec3 dims(10, 9, 8);
        std::vector<float> data(std::size_t(dims.x * dims.y * dims.z));
        for (std::size_t n = 0; n < data.size(); ++n) {
            data[n] = float(n);
        }
        const auto at = [&](int i, int j, int k) {
            return data[std::size_t(i + dims.x * (j + dims.y * k))];
        };
        const int slot = 4 + 2 * 3;
        std::vector<float> out(std::size_t(slot * slot * slot));
        const auto got = [&](int a, int b, int c) {
            return out[std::size_t(a + slot * (b + slot * c))];
        };
        extractBrick<float>(data.data(), dims, {0, 4, 4}, 3, slot, BrickEdge::Clamp, out.data());
        QCOMPARE(got(3, 3, 3), at(0, 4, 4)); // the core's first voxel
        QCOMPARE(got(0, 3, 3), at(0, 4, 4)); // before the edge: clamped
        QCOMPARE(got(9, 9, 9), at(6, 8, 7)); // beyond: clamped on y and z
        extractBrick<float>(data.data(), dims, {0, 4, 4}, 3, slot, BrickEdge::Mirror, out.data());
        QCOMPARE(got(0, 3, 3), at(3, 4, 4)); // i = -3 mirrors to 3
        QCOMPARE(got(3, 9, 9), at(0, 6, 4)); // j = 10 mirrors to 6 (of 9), k = 10 to 4 (of 8)
    }

    void gradientSlotHoldsCentralDifferences() {
        const glm::ivec3 dims(10, 9, 8);
        std::vector<std::int16_t> data(std::size_t(dims.x * dims.y * dims.z));
        const auto f = [](int i, int j, int k) { return 3 * i * i - 5 * j + 7 * k; };
        for (int k = 0; k < dims.z; ++k) {
            for (int j = 0; j < dims.y; ++j) {
                for (int i = 0; i < dims.x; ++i) {
                    data[std::size_t(i + dims.x * (j + dims.y * k))] = std::int16_t(f(i, j, k));
                }
            }
        }
        const int slot = 4 + 2 * 3;
        std::vector<std::int16_t> out(std::size_t(slot * slot * slot) * 4);
        const double unit = 0.5;
        extractGradientBrick<std::int16_t>(data.data(), dims, {4, 4, 0}, 3, slot, unit, out.data());
        const auto got = [&](int a, int b, int c, int ch) {
            return out[4 * std::size_t(a + slot * (b + slot * c)) + std::size_t(ch)];
        };
        // Voxel (5, 5, 4) sits at slot (4, 4, 7): d/di = 6i = 30, d/dj = -5, d/dk = 7; / unit.
        QCOMPARE(got(4, 4, 7, 0), std::int16_t(60));
        QCOMPARE(got(4, 4, 7, 1), std::int16_t(-10));
        QCOMPARE(got(4, 4, 7, 2), std::int16_t(14));
        QCOMPARE(got(4, 4, 7, 3), std::int16_t(0));
        // k = 0 lies at slot c = 3: the neighbour below is clamped, so half of one step.
        QCOMPARE(got(4, 4, 3, 2), std::int16_t(7));
    }
};

QTEST_GUILESS_MAIN(TestBrickResidency)
#include "test_brick_residency.moc"
