// BrickBoxes, the tight sample boxes of the GPU's bricks: which level-0 cells
// can show (through the level the brick is drawn from, and the clip box), the
// box of those cells per brick, the neighbour shell, and the level voxels a
// box's filters read (storedBox).
#include <QTest>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include "core/volume/BrickBoxes.h"
#include "core/volume/LodPyramid.h"
#include "tests/core/raycast/RaycastScenes.h"

using namespace lucent;
using namespace lucent::test;

namespace {

std::size_t idOf(glm::ivec3 c, glm::ivec3 per) {
    return std::size_t(c.x) + std::size_t(per.x) * (std::size_t(c.y) + std::size_t(per.y) * c.z);
}

// 40 x 32 x 24: cells of 8 are 5 x 4 x 3; bricks of 16 are 3 x 2 x 2. Zero
// but for two voxels of 100: (20, 12, 9), whose cells (with their overlap of
// 3) are (2, 1, 0) and (2, 1, 1), and (37, 30, 22), in the corner cell (4, 3, 2).
const glm::ivec3 kDims(40, 32, 24);

Volume hotVolume() {
    return makeVolume(kDims, [](int i, int j, int k) {
        return (i == 20 && j == 12 && k == 9) || (i == 37 && j == 30 && k == 22) ? 100.0 : 0.0;
    });
}

bool above10(double, double hi) {
    return hi > 10.0;
}

bool above20(double, double hi) {
    return hi > 20.0;
}

std::vector<std::uint8_t> cellsAt(glm::ivec3 per, const std::vector<glm::ivec3>& on) {
    std::vector<std::uint8_t> cells(std::size_t(per.x * per.y * per.z), 0);
    for (const glm::ivec3 c : on) {
        cells[idOf(c, per)] = 1;
    }
    return cells;
}

std::vector<glm::ivec3> cellsOn(const std::vector<std::uint8_t>& cells, glm::ivec3 per) {
    std::vector<glm::ivec3> on;
    for (int z = 0; z < per.z; ++z) {
        for (int y = 0; y < per.y; ++y) {
            for (int x = 0; x < per.x; ++x) {
                if (cells[idOf({x, y, z}, per)] != 0) {
                    on.emplace_back(x, y, z);
                }
            }
        }
    }
    return on;
}

std::size_t boxCount(const std::vector<std::optional<SampleBox>>& boxes) {
    return std::size_t(
        std::count_if(boxes.begin(), boxes.end(), [](const auto& b) { return b.has_value(); }));
}

void checkBox(const std::optional<SampleBox>& box, glm::ivec3 lo, glm::ivec3 hi, bool contributes) {
    QVERIFY(box.has_value());
    QCOMPARE(box->lo, lo);
    QCOMPARE(box->hi, hi);
    QCOMPARE(box->contributes, contributes);
}

} // namespace

class TestBrickBoxes : public QObject {
    Q_OBJECT

private slots:
    void gridsOfCellsAndBricks() {
        const BrickBoxes b(kDims, 16, 8);
        QCOMPARE(b.brickSize(), 16);
        QCOMPARE(b.cellsPerAxis(), glm::ivec3(5, 4, 3));
        QCOMPARE(b.bricksPerAxis(), glm::ivec3(3, 2, 2));
        QCOMPARE(b.cellCount(), std::size_t(60));
        QCOMPARE(b.brickCount(), std::size_t(12));
        QCOMPARE(b.brickOfCell({2, 1, 1}), std::uint32_t(1));      // voxel (16, 8, 8)
        QCOMPARE(b.brickOfLastVoxel({2, 1, 1}), std::uint32_t(1)); // voxel (23, 15, 15)
        QCOMPARE(b.brickOfCell({4, 3, 2}), std::uint32_t(11));     // brick (2, 1, 1)
        // Bricks of 12: cell (1, 1, 1) spans voxels 8 .. 15, bricks 0 and 1 on each axis.
        const BrickBoxes b12(kDims, 12, 8);
        QCOMPARE(b12.bricksPerAxis(), glm::ivec3(4, 3, 2));
        QCOMPARE(b12.brickOfCell({1, 1, 1}), std::uint32_t(0));
        QCOMPARE(b12.brickOfLastVoxel({1, 1, 1}), std::uint32_t(1 + 4 * (1 + 3 * 1)));
        // The last cell of a volume of 20 ends at voxel 19.
        const BrickBoxes odd({20, 20, 20}, 16, 8);
        QCOMPARE(odd.cellsPerAxis(), glm::ivec3(3));
        QCOMPARE(odd.brickOfLastVoxel({2, 2, 2}), std::uint32_t(7));
        QCOMPARE(odd.brickOfLastVoxel({1, 1, 1}), std::uint32_t(0)); // voxel 15
    }

    void levelZeroCellsAreTheirOwn() {
        const Volume v = hotVolume();
        const BrickGrid cells(v, 8, 3);
        const BrickBoxes b(kDims, 16, 8);
        const std::vector<std::uint32_t> at = b.levelCellOf(cells, 0);
        QCOMPARE(at.size(), b.cellCount());
        for (std::size_t n = 0; n < at.size(); ++n) {
            QCOMPARE(at[n], std::uint32_t(n));
        }
    }

    // Each level-0 cell maps to the level cell holding its centre (worked out
    // by hand for 40 x 30 x 20, whose last cells are short).
    void levelCellHoldsTheCentre() {
        const glm::ivec3 dims(40, 30, 20);
        const Volume v = makeVolume(dims, [](int i, int j, int k) { return i + j + k; });
        const BrickBoxes b(dims, 16, 8);
        QCOMPARE(b.cellsPerAxis(), glm::ivec3(5, 4, 3));
        const Volume l1 = downsampleByTwo(v);
        const Volume l2 = downsampleByTwo(l1);
        QCOMPARE(l1.dims(), glm::ivec3(20, 15, 10));
        QCOMPARE(l2.dims(), glm::ivec3(10, 8, 5));
        const BrickGrid g1(l1, 8, 3), g2(l2, 8, 3);
        QCOMPARE(g1.bricksPerAxis(), glm::ivec3(3, 2, 2));
        QCOMPARE(g2.bricksPerAxis(), glm::ivec3(2, 1, 1));
        // Level 1: a level-0 cell c of 8 has its centre at 8c + 3.5 (the short
        // ones: y 26.5, z 17.5), at level 1 (p - 0.5) / 2.
        const int x1[5] = {0, 0, 1, 1, 2}, y1[4] = {0, 0, 1, 1}, z1[3] = {0, 0, 1};
        // Level 2: (p - 1.5) / 4: x 0.5, 2.5, 4.5, 6.5, 8.5 -> cells 0 0 0 0 1.
        const int x2[5] = {0, 0, 0, 0, 1};
        const std::vector<std::uint32_t> at1 = b.levelCellOf(g1, 1);
        const std::vector<std::uint32_t> at2 = b.levelCellOf(g2, 2);
        QCOMPARE(at1.size(), b.cellCount());
        QCOMPARE(at2.size(), b.cellCount());
        for (int z = 0; z < 3; ++z) {
            for (int y = 0; y < 4; ++y) {
                for (int x = 0; x < 5; ++x) {
                    const std::size_t c = idOf({x, y, z}, b.cellsPerAxis());
                    QCOMPARE(at1[c], g1.idOf({x1[x], y1[y], z1[z]}));
                    QCOMPARE(at2[c], g2.idOf({x2[x], 0, 0}));
                }
            }
        }
    }

    // What levelCellOf promises: every read of a sample in a level-0 cell at
    // the level (filters of reach 1 and 2) lies in the level cell's range,
    // its core grown by the overlap of 3.
    void levelCellCoversTheReads() {
        for (const glm::ivec3 dims : {glm::ivec3(40, 30, 20), glm::ivec3(57, 33, 70)}) {
            const Volume v = makeVolume(dims, [](int, int, int) { return 0.0; });
            const LodPyramid pyramid(v, 4);
            const BrickBoxes b(dims, 16, 8);
            for (int level = 1; level < pyramid.levelCount(); ++level) {
                const BrickGrid g(pyramid.level(level), 8, 3);
                const std::vector<std::uint32_t> at = b.levelCellOf(g, level);
                const glm::ivec3 per = b.cellsPerAxis();
                for (int z = 0; z < per.z; ++z) {
                    for (int y = 0; y < per.y; ++y) {
                        for (int x = 0; x < per.x; ++x) {
                            const glm::ivec3 c(x, y, z);
                            const SampleBox box{c * 8, glm::min(c * 8 + 8, dims), true};
                            const StoredBox s = storedBox(box, level, FilterReach{1, 2});
                            const Brick& cell = g.bricks()[at[idOf(c, per)]];
                            const QString where = QString("level %1, cell (%2 %3 %4)")
                                                      .arg(level)
                                                      .arg(x)
                                                      .arg(y)
                                                      .arg(z);
                            QVERIFY2(glm::all(glm::greaterThanEqual(s.lo, cell.first - 3)),
                                     qPrintable(where));
                            QVERIFY2(glm::all(glm::lessThanEqual(s.lo + s.size, cell.last + 3)),
                                     qPrintable(where));
                        }
                    }
                }
            }
        }
    }

    void visibleCellsFollowTheRangesAndTheClipBox() {
        const Volume v = hotVolume();
        const BrickGrid cells(v, 8, 3);
        const BrickBoxes b(kDims, 16, 8);
        const glm::ivec3 per = b.cellsPerAxis();
        using Cells = std::vector<glm::ivec3>;
        QCOMPARE(cellsOn(b.visibleCells(cells, 0, above10, ClipBox{}), per),
                 (Cells{{2, 1, 0}, {2, 1, 1}, {4, 3, 2}}));
        QCOMPARE(cellsOn(b.visibleCells(cells, 0, above20, ClipBox{}), per).size(), std::size_t(3));
        QVERIFY(cellsOn(b.visibleCells(
                            cells, 0, [](double, double hi) { return hi > 100.0; }, ClipBox{}),
                        per)
                    .empty());
        // Cells z = 1 start at 8: a clip box up to 7.99 leaves them out, up to 8 not.
        ClipBox clip;
        clip.hi.z = 7.99;
        QCOMPARE(cellsOn(b.visibleCells(cells, 0, above10, clip), per), (Cells{{2, 1, 0}}));
        clip.hi.z = 8.0;
        QCOMPARE(cellsOn(b.visibleCells(cells, 0, above10, clip), per),
                 (Cells{{2, 1, 0}, {2, 1, 1}}));
        // Cells x = 2 end at 24: a clip box from 24.5 leaves only the corner.
        clip = ClipBox{};
        clip.lo.x = 24.5;
        QCOMPARE(cellsOn(b.visibleCells(cells, 0, above10, clip), per), (Cells{{4, 3, 2}}));
        // From 23.5 the last half voxel of cells x = 2 is in.
        clip.lo.x = 23.5;
        QCOMPARE(cellsOn(b.visibleCells(cells, 0, above10, clip), per),
                 (Cells{{2, 1, 0}, {2, 1, 1}, {4, 3, 2}}));
        // An empty clip box (lo > hi) leaves nothing.
        clip = ClipBox{};
        clip.lo.x = 30.0;
        clip.hi.x = 20.0;
        QVERIFY(cellsOn(b.visibleCells(cells, 0, above10, clip), per).empty());
    }

    // At level 1 the hot voxels average to 12.5 at (10, 6, 4) and (18, 15, 11):
    // visibility comes from the level's cells, which cover more level-0 cells.
    void visibleCellsAtACoarserLevel() {
        const Volume v = hotVolume();
        const Volume l1 = downsampleByTwo(v);
        QCOMPARE(l1.value(10, 6, 4), 12.5);
        QCOMPARE(l1.value(18, 15, 11), 12.5);
        const BrickGrid g1(l1, 8, 3);
        const BrickBoxes b(kDims, 16, 8);
        const glm::ivec3 per = b.cellsPerAxis();
        const std::vector<std::uint8_t> seen = b.visibleCells(g1, 1, above10, ClipBox{});
        QCOMPARE(seen.size(), b.cellCount());
        // Level cells (padded by 3) holding (10, 6, 4): x 0-1, y 0-1, z 0, so
        // level-0 cells x 0-3, y 0-3, z 0-1; holding (18, 15, 11): x 1-2, y 1,
        // z 1, so level-0 cells x 2-4, y 2-3, z 2.
        int count = 0;
        for (int z = 0; z < per.z; ++z) {
            for (int y = 0; y < per.y; ++y) {
                for (int x = 0; x < per.x; ++x) {
                    const bool want = (x <= 3 && z <= 1) || (x >= 2 && y >= 2 && z == 2);
                    QCOMPARE(seen[idOf({x, y, z}, per)] != 0, want);
                    count += want ? 1 : 0;
                }
            }
        }
        QCOMPARE(count, 38);
        // 12.5 is below 20: nothing at level 1, though level 0 shows three cells.
        const std::vector<std::uint8_t> none = b.visibleCells(g1, 1, above20, ClipBox{});
        QCOMPARE(std::count(none.begin(), none.end(), std::uint8_t(1)), std::ptrdiff_t(0));
    }

    void boxesBoundTheVisibleCellsOfEachBrick() {
        const Volume v = hotVolume();
        const BrickGrid cells(v, 8, 3);
        const BrickBoxes b(kDims, 16, 8);
        const auto boxes = b.boxes(b.visibleCells(cells, 0, above10, ClipBox{}), false);
        QCOMPARE(boxes.size(), b.brickCount());
        QCOMPARE(boxCount(boxes), std::size_t(2));
        checkBox(boxes[1], {16, 8, 0}, {24, 16, 16}, true);    // brick (1, 0, 0)
        checkBox(boxes[11], {32, 24, 16}, {40, 32, 24}, true); // brick (2, 1, 1)
        // Cells chosen by hand: two in brick 0, two side by side in brick 1.
        const glm::ivec3 per = b.cellsPerAxis();
        const auto mine =
            b.boxes(cellsAt(per, {{0, 0, 0}, {1, 1, 1}, {2, 0, 0}, {3, 0, 0}}), false);
        QCOMPARE(boxCount(mine), std::size_t(2));
        checkBox(mine[0], {0, 0, 0}, {16, 16, 16}, true);
        checkBox(mine[1], {16, 0, 0}, {32, 8, 8}, true);
        QCOMPARE(boxCount(b.boxes(cellsAt(per, {}), false)), std::size_t(0));
        QCOMPARE(boxCount(b.boxes(cellsAt(per, {}), true)), std::size_t(0));
    }

    void clipBoxTrimsTheBoxes() {
        const Volume v = hotVolume();
        const BrickGrid cells(v, 8, 3);
        const BrickBoxes b(kDims, 16, 8);
        ClipBox clip;
        clip.hi.z = 7.99;
        const auto boxes = b.boxes(b.visibleCells(cells, 0, above10, clip), false);
        QCOMPARE(boxCount(boxes), std::size_t(1));
        checkBox(boxes[1], {16, 8, 0}, {24, 16, 8}, true);
        QVERIFY(!boxes[11]);
    }

    // With neighbours the 26 cells around a visible one count; bricks holding
    // only such cells do not contribute.
    void neighboursAddCellsThatDoNotContribute() {
        const BrickBoxes b(kDims, 16, 8);
        const glm::ivec3 per = b.cellsPerAxis();
        const std::vector<std::uint8_t> one = cellsAt(per, {{2, 1, 0}});
        const auto plain = b.boxes(one, false);
        QCOMPARE(boxCount(plain), std::size_t(1));
        checkBox(plain[1], {16, 8, 0}, {24, 16, 8}, true);
        // Neighbours: cells x 1-3, y 0-2, z 0-1.
        const auto shell = b.boxes(one, true);
        QCOMPARE(boxCount(shell), std::size_t(4));
        checkBox(shell[0], {8, 0, 0}, {16, 16, 16}, false);   // brick (0, 0, 0)
        checkBox(shell[1], {16, 0, 0}, {32, 16, 16}, true);   // brick (1, 0, 0)
        checkBox(shell[3], {8, 16, 0}, {16, 24, 16}, false);  // brick (0, 1, 0)
        checkBox(shell[4], {16, 16, 0}, {32, 24, 16}, false); // brick (1, 1, 0)
        // At the far corner the shell stops at the volume: cells x 3-4, y 2-3, z 1-2.
        const auto corner = b.boxes(cellsAt(per, {{4, 3, 2}}), true);
        QCOMPARE(boxCount(corner), std::size_t(4));
        checkBox(corner[4], {24, 16, 8}, {32, 32, 16}, false);   // brick (1, 1, 0)
        checkBox(corner[5], {32, 16, 8}, {40, 32, 16}, false);   // brick (2, 1, 0)
        checkBox(corner[10], {24, 16, 16}, {32, 32, 24}, false); // brick (1, 1, 1)
        checkBox(corner[11], {32, 16, 16}, {40, 32, 24}, true);  // brick (2, 1, 1)
    }

    // Bricks of 12: a cell of 8 straddling bricks counts in each of them,
    // clipped to its core.
    void cellsStraddlingBricksCountInEach() {
        const BrickBoxes b(kDims, 12, 8);
        const glm::ivec3 per = b.cellsPerAxis(), bricks = b.bricksPerAxis();
        QCOMPARE(bricks, glm::ivec3(4, 3, 2));
        const auto boxes = b.boxes(cellsAt(per, {{1, 1, 1}}), false); // voxels 8 .. 15
        QCOMPARE(boxCount(boxes), std::size_t(8));
        for (int k = 0; k < 2; ++k) {
            for (int j = 0; j < 2; ++j) {
                for (int i = 0; i < 2; ++i) {
                    const glm::ivec3 at(i, j, k);
                    checkBox(boxes[idOf(at, bricks)], glm::max(glm::ivec3(8), at * 12),
                             glm::min(glm::ivec3(16), (at + 1) * 12), true);
                }
            }
        }
        // With cell (2, 0, 0) too (voxels x 16 .. 23, brick x 1 alone), brick
        // (1, 0, 0) bounds both.
        const auto two = b.boxes(cellsAt(per, {{1, 1, 1}, {2, 0, 0}}), false);
        QCOMPARE(boxCount(two), std::size_t(8));
        checkBox(two[1], {12, 0, 0}, {24, 12, 12}, true);
        // The last cell (x 32 .. 39) straddles bricks 2 (24 .. 35) and 3 (36 .. 39).
        const auto last = b.boxes(cellsAt(per, {{4, 0, 0}}), false);
        QCOMPARE(boxCount(last), std::size_t(2));
        checkBox(last[2], {32, 0, 0}, {36, 8, 8}, true);
        checkBox(last[3], {36, 0, 0}, {40, 8, 8}, true);
    }

    // What each filter reads (trilinear 0 and 1, differences and the spline
    // 1 and 2) and a guard texel on each side against texture-coordinate rounding.
    void filterReaches() {
        const FilterReach linear = filterReach(false, false);
        QCOMPARE(linear.below, 1);
        QCOMPARE(linear.above, 2);
        for (const FilterReach r :
             {filterReach(true, false), filterReach(false, true), filterReach(true, true)}) {
            QCOMPARE(r.below, 2);
            QCOMPARE(r.above, 3);
        }
    }

    // The box (16, 8, 0) .. (24, 16, 16) by hand at levels 0, 1 and 2.
    void storedBoxByHand() {
        const SampleBox box{{16, 8, 0}, {24, 16, 16}, true};
        const FilterReach linear{0, 1}, cubic{1, 2};
        // Level 0: [lo, hi] and [lo - 1, hi + 1].
        StoredBox s = storedBox(box, 0, linear);
        QCOMPARE(s.lo, glm::ivec3(16, 8, 0));
        QCOMPARE(s.size, glm::ivec3(9, 9, 17));
        s = storedBox(box, 0, cubic);
        QCOMPARE(s.lo, glm::ivec3(15, 7, -1));
        QCOMPARE(s.size, glm::ivec3(11, 11, 19));
        // Level 1: positions (p - 0.5) / 2 in [7.75, 11.75) x [3.75, 7.75) x
        // [-0.25, 7.75): floors 7-11, 3-7, -1-7.
        s = storedBox(box, 1, linear);
        QCOMPARE(s.lo, glm::ivec3(7, 3, -1));
        QCOMPARE(s.size, glm::ivec3(6, 6, 10));
        s = storedBox(box, 1, cubic);
        QCOMPARE(s.lo, glm::ivec3(6, 2, -2));
        QCOMPARE(s.size, glm::ivec3(8, 8, 12));
        // Level 2: (p - 1.5) / 4 in [3.625, 5.625) x [1.625, 3.625) x [-0.375, 3.625).
        s = storedBox(box, 2, linear);
        QCOMPARE(s.lo, glm::ivec3(3, 1, -1));
        QCOMPARE(s.size, glm::ivec3(4, 4, 6));
    }

    // Random boxes and levels: every floor(q) - below .. floor(q) + above of a
    // sample in the box lies in the stored box, and the stored box is no larger.
    void storedBoxIsTightAroundTheReads() {
        std::mt19937 rng(7);
        std::uniform_int_distribution<int> corner(-3, 40), extent(1, 20);
        for (int n = 0; n < 200; ++n) {
            SampleBox box;
            box.lo = {corner(rng), corner(rng), corner(rng)};
            box.hi = box.lo + glm::ivec3(extent(rng), extent(rng), extent(rng));
            const int level = n % 4;
            const FilterReach reach = n % 3 == 0 ? FilterReach{1, 2} : FilterReach{0, 1};
            const StoredBox s = storedBox(box, level, reach);
            for (int a = 0; a < 3; ++a) {
                int lo = 1 << 30, hi = -(1 << 30);
                // Samples 1/64 apart up to just below hi.
                for (int t = box.lo[a] * 64; t < box.hi[a] * 64; ++t) {
                    const double q = LodPyramid::fromLevel0(glm::dvec3(t / 64.0), level).x;
                    lo = std::min(lo, int(std::floor(q)) - reach.below);
                    hi = std::max(hi, int(std::floor(q)) + reach.above);
                }
                QCOMPARE(s.lo[a], lo);
                QCOMPARE(s.lo[a] + s.size[a] - 1, hi);
            }
        }
    }
};

QTEST_GUILESS_MAIN(TestBrickBoxes)
#include "test_brick_boxes.moc"
