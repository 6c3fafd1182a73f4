// chooseLevels over small octrees built by hand: everything at level 0 when it
// fits, a BudgetError when not even the roots do, PerBrick refining the most
// worth first while it fits, Uniform taking the finest level that fits, and
// the shown nodes covering every root exactly once.
#include <QTest>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/volume/BrickLevels.h"
#include "core/volume/BrickResidency.h"

using namespace lucent;

namespace {

constexpr std::size_t kMiB = std::size_t(1) << 20;

struct Tree {
    std::vector<LodNode> nodes;
    std::vector<std::size_t> roots;

    std::size_t add(int level, std::size_t bytes, double worth,
                    std::vector<std::size_t> children = {}) {
        nodes.push_back(LodNode{level, bytes, worth, std::move(children)});
        return nodes.size() - 1;
    }
    std::size_t root(int level, std::size_t bytes, double worth,
                     std::vector<std::size_t> children) {
        roots.push_back(add(level, bytes, worth, std::move(children)));
        return roots.back();
    }
    LevelChoice choose(std::size_t budget, LodPolicy policy) const {
        return chooseLevels(nodes, roots, budget, policy);
    }
};

std::vector<std::size_t> sorted(std::vector<std::size_t> v) {
    std::sort(v.begin(), v.end());
    return v;
}

std::size_t bytesOf(const Tree& t, const std::vector<std::size_t>& shown) {
    std::size_t sum = 0;
    for (const std::size_t n : shown) {
        sum += t.nodes[n].bytes;
    }
    return sum;
}

// Every root-to-leaf path meets exactly one shown node (so no node is shown
// with its ancestor, and every root is covered once).
void checkCover(const Tree& t, const std::vector<std::size_t>& shown) {
    std::vector<char> isShown(t.nodes.size(), 0);
    for (const std::size_t n : shown) {
        QVERIFY(n < t.nodes.size());
        QVERIFY2(isShown[n] == 0, "a node shown twice");
        isShown[n] = 1;
    }
    std::vector<int> reached(t.nodes.size(), 0);
    std::vector<std::pair<std::size_t, int>> stack; // node, shown nodes above and at it
    for (const std::size_t r : t.roots) {
        stack.emplace_back(r, isShown[r]);
    }
    while (!stack.empty()) {
        const auto [n, above] = stack.back();
        stack.pop_back();
        ++reached[n];
        if (t.nodes[n].children.empty()) {
            QVERIFY2(above == 1,
                     qPrintable(QString("leaf %1 is under %2 shown nodes").arg(n).arg(above)));
        }
        for (const std::size_t c : t.nodes[n].children) {
            stack.emplace_back(c, above + isShown[c]);
        }
    }
    for (const std::size_t n : shown) {
        QVERIFY2(reached[n] == 1, "a shown node outside the roots' trees");
    }
}

// A node of `level` with 1 .. fanout children of level - 1 each, down to
// level 0; random bytes (0 .. 400) and worth. monotone: a node needs no more
// bytes than its children.
std::size_t grow(Tree& t, int level, int fanout, std::mt19937& rng, bool monotone) {
    std::uniform_int_distribution<int> fan(1, fanout);
    std::uniform_int_distribution<std::size_t> bytes(0, 400);
    std::uniform_real_distribution<double> worth(0.01, 10.0);
    std::vector<std::size_t> children;
    if (level > 0) {
        const int count = fan(rng);
        for (int c = 0; c < count; ++c) {
            children.push_back(grow(t, level - 1, fanout, rng, monotone));
        }
    }
    std::size_t b = bytes(rng);
    if (monotone && !children.empty()) {
        // No more than its children need: refining never frees bytes.
        std::size_t sum = 0;
        for (const std::size_t c : children) {
            sum += t.nodes[c].bytes;
        }
        b = std::min(b, sum);
    }
    return t.add(level, b, worth(rng), std::move(children));
}

} // namespace

class TestBrickLevels : public QObject {
    Q_OBJECT

private slots:
    void noRootsNothingShown() {
        const LevelChoice c = chooseLevels({}, {}, 0, LodPolicy::PerBrick);
        QVERIFY(c.shown.empty());
        QCOMPARE(c.bytes, std::size_t(0));
        QVERIFY(c.coarsened.empty());
    }

    // Two roots of level 1 with eight children each, some of them empty:
    // level 0 fits, so it is all shown.
    void everythingAtLevelZeroWhenItFits() {
        Tree t;
        std::vector<std::size_t> fine;
        for (int r = 0; r < 2; ++r) {
            std::vector<std::size_t> children;
            for (int c = 0; c < 8; ++c) {
                children.push_back(t.add(0, c % 3 == 0 ? 0 : 10 + std::size_t(c), 1.0));
                fine.push_back(children.back());
            }
            t.root(1, 50, 2.0 - r, children);
        }
        const std::size_t need = bytesOf(t, fine);
        for (const LodPolicy p : {LodPolicy::PerBrick, LodPolicy::Uniform}) {
            for (const std::size_t budget : {need, need + 1, std::size_t(1) << 40}) {
                const LevelChoice c = t.choose(budget, p);
                QCOMPARE(sorted(c.shown), sorted(fine));
                QCOMPARE(c.bytes, need);
                QCOMPARE(c.coarsened, std::string());
            }
            // One byte less and level 0 no longer fits: something is coarser.
            const LevelChoice c = t.choose(need - 1, p);
            QVERIFY(!c.coarsened.empty());
            QVERIFY(sorted(c.shown) != sorted(fine));
            QVERIFY(c.bytes <= need - 1);
            checkCover(t, c.shown);
        }
    }

    void budgetErrorWhenTheRootsDoNotFit() {
        Tree t;
        for (int r = 0; r < 2; ++r) {
            t.root(1, 2 * kMiB, 1.0, {t.add(0, 5 * kMiB, 1.0), t.add(0, 5 * kMiB, 1.0)});
        }
        for (const LodPolicy p : {LodPolicy::PerBrick, LodPolicy::Uniform}) {
            try {
                t.choose(3 * kMiB, p);
                QFAIL("a budget of 3 MiB took roots of 4 MiB");
            } catch (const BudgetError& e) {
                const std::string what = e.what();
                QVERIFY2(what.find("3 MiB") != std::string::npos, e.what()); // the budget
                QVERIFY2(what.find("4 MiB") != std::string::npos, e.what()); // the need
            }
            QVERIFY_THROWS_EXCEPTION(std::runtime_error, t.choose(0, p));
            // Exactly what the roots need: the roots, coarsened.
            const LevelChoice c = t.choose(4 * kMiB, p);
            QCOMPARE(sorted(c.shown), sorted(t.roots));
            QCOMPARE(c.bytes, 4 * kMiB);
            QVERIFY(!c.coarsened.empty());
        }
    }

    // Roots A and B of level 1 (10 bytes), each refining into 2 x 20 (+30):
    // a budget of 55 takes one refinement, the one worth more, whatever the order.
    void perBrickRefinesTheMostWorthFirst() {
        for (const bool aFirst : {true, false}) {
            for (const bool aWorthMore : {true, false}) {
                Tree t;
                const std::size_t a0 = t.add(0, 20, 1.0), a1 = t.add(0, 20, 1.0);
                const std::size_t b0 = t.add(0, 20, 1.0), b1 = t.add(0, 20, 1.0);
                const std::size_t a = t.add(1, 10, aWorthMore ? 5.0 : 1.0, {a0, a1});
                const std::size_t b = t.add(1, 10, aWorthMore ? 1.0 : 5.0, {b0, b1});
                t.roots = aFirst ? std::vector<std::size_t>{a, b} : std::vector<std::size_t>{b, a};
                const LevelChoice c = t.choose(55, LodPolicy::PerBrick);
                const std::vector<std::size_t> want = aWorthMore
                                                          ? std::vector<std::size_t>{a0, a1, b}
                                                          : std::vector<std::size_t>{b0, b1, a};
                QCOMPARE(sorted(c.shown), sorted(want));
                QCOMPARE(c.bytes, std::size_t(50));
                QVERIFY(!c.coarsened.empty());
                checkCover(t, c.shown);
            }
        }
    }

    // A (worth 10) refines for +50, B (5) for +100, C (1) for +20, from 30:
    // with 105, A fits, B then does not, but C still does.
    void perBrickStillTakesACheaperRefinement() {
        Tree t;
        const std::size_t a0 = t.add(0, 30, 1.0), a1 = t.add(0, 30, 1.0);
        const std::size_t b0 = t.add(0, 55, 1.0), b1 = t.add(0, 55, 1.0);
        const std::size_t c0 = t.add(0, 15, 1.0), c1 = t.add(0, 15, 1.0);
        const std::size_t a = t.root(1, 10, 10.0, {a0, a1});
        const std::size_t b = t.root(1, 10, 5.0, {b0, b1});
        const std::size_t c = t.root(1, 10, 1.0, {c0, c1});
        LevelChoice got = t.choose(105, LodPolicy::PerBrick);
        QCOMPARE(sorted(got.shown), sorted({a0, a1, b, c0, c1}));
        QCOMPARE(got.bytes, std::size_t(100));
        // With 79, A does not fit (80) either, but C does.
        got = t.choose(79, LodPolicy::PerBrick);
        QCOMPARE(sorted(got.shown), sorted({a, b, c0, c1}));
        QCOMPARE(got.bytes, std::size_t(50));
        // With 49 nothing refines.
        got = t.choose(49, LodPolicy::PerBrick);
        QCOMPARE(sorted(got.shown), sorted({a, b, c}));
        QCOMPARE(got.bytes, std::size_t(30));
        // With 200 everything refines: level 0 fits.
        got = t.choose(200, LodPolicy::PerBrick);
        QCOMPARE(sorted(got.shown), sorted({a0, a1, b0, b1, c0, c1}));
        QCOMPARE(got.bytes, std::size_t(200));
        QVERIFY(got.coarsened.empty());
    }

    // A refinement that did not fit when its turn came, but fits once a later
    // refinement has freed bytes (a coarse box larger than its children's),
    // is still taken. From 120: B (worth 5, +90) does not fit 150 at first,
    // C (1, +190) never does, A (0.1, -90) frees 90; then B fits (120).
    void perBrickTakesARefinementThatFitsOnceBytesAreFreed() {
        Tree t;
        const std::size_t a0 = t.add(0, 5, 1.0), a1 = t.add(0, 5, 1.0);
        const std::size_t b0 = t.add(0, 50, 1.0), b1 = t.add(0, 50, 1.0);
        const std::size_t c0 = t.add(0, 200, 1.0);
        t.root(1, 100, 0.1, {a0, a1});
        const std::size_t b = t.root(1, 10, 5.0, {b0, b1});
        const std::size_t c = t.root(1, 10, 1.0, {c0});
        const LevelChoice got = t.choose(150, LodPolicy::PerBrick);
        checkCover(t, got.shown);
        QVERIFY2(std::find(got.shown.begin(), got.shown.end(), b) == got.shown.end(),
                 qPrintable(QString("B (the most worth) stays coarse with %1 of 150 bytes used")
                                .arg(got.bytes)));
        QCOMPARE(sorted(got.shown), sorted({a0, a1, b0, b1, c}));
        QCOMPARE(got.bytes, std::size_t(120));
    }

    // Three levels: refining goes on below a refined root, within the budget.
    void perBrickRefinesDownSeveralLevels() {
        Tree t;
        const std::size_t x00 = t.add(0, 40, 1.0), x01 = t.add(0, 40, 1.0);
        const std::size_t x10 = t.add(0, 40, 1.0);
        const std::size_t x0 = t.add(1, 20, 3.0, {x00, x01});
        const std::size_t x1 = t.add(1, 20, 1.0, {x10});
        const std::size_t x = t.root(2, 10, 1.0, {x0, x1});
        const std::size_t y0 = t.add(0, 400, 1.0);
        const std::size_t y1 = t.add(1, 100, 1.0, {y0});
        const std::size_t y = t.root(2, 10, 0.4, {y1});
        // 20 -> X: 50 -> X0: 110 -> X1: 130; Y would then need 220.
        LevelChoice c = t.choose(130, LodPolicy::PerBrick);
        QCOMPARE(sorted(c.shown), sorted({x00, x01, x10, y}));
        QCOMPARE(c.bytes, std::size_t(130));
        checkCover(t, c.shown);
        // 99: X (50), then not X0 (110) but X1 (70).
        c = t.choose(99, LodPolicy::PerBrick);
        QCOMPARE(sorted(c.shown), sorted({x0, x10, y}));
        QCOMPARE(c.bytes, std::size_t(20 + 40 + 10));
        checkCover(t, c.shown);
        // Uniform: level 0 needs 520, level 1 140, level 2 20.
        QCOMPARE(sorted(t.choose(519, LodPolicy::Uniform).shown), sorted({x0, x1, y1}));
        QCOMPARE(t.choose(140, LodPolicy::Uniform).bytes, std::size_t(140));
        QCOMPARE(sorted(t.choose(139, LodPolicy::Uniform).shown), sorted({x, y}));
        QCOMPARE(sorted(t.choose(520, LodPolicy::Uniform).shown), sorted({x00, x01, x10, y0}));
    }

    // A refinement's gain is its worth times the square of its voxel size
    // (4^level: the error of a blurred surface grows faster than its voxel),
    // over the bytes it adds. R's free refinement first; then P (1 x 16 / 11)
    // before q (3 x 4 / 11), though q is worth three times as much: the
    // coarsest voxels go first. By 2^level q would win (6 / 11 against 4 / 11).
    void coarserRefinementsWeighMore() {
        Tree t;
        const std::size_t p0 = t.add(0, 100, 1.0);
        const std::size_t p1 = t.add(1, 20, 1.0, {p0});
        const std::size_t p = t.root(2, 10, 1.0, {p1});
        const std::size_t q0 = t.add(0, 20, 1.0);
        const std::size_t q = t.add(1, 10, 3.0, {q0});
        t.root(2, 10, 10.0, {q});
        const LevelChoice c = t.choose(30, LodPolicy::PerBrick);
        QCOMPARE(sorted(c.shown), sorted({p1, q}));
        QCOMPARE(c.bytes, std::size_t(30));
        (void)p;
        // With room for both, both.
        const LevelChoice d = t.choose(40, LodPolicy::PerBrick);
        QCOMPARE(sorted(d.shown), sorted({p1, q0}));
    }

    // Uniform: the finest level whose nodes all fit, for all of them, though
    // PerBrick would take one branch finer.
    void uniformTakesTheFinestLevelThatFits() {
        Tree t;
        const std::size_t a0 = t.add(0, 15, 1.0), a1 = t.add(0, 15, 1.0);
        const std::size_t b0 = t.add(0, 100, 1.0), b1 = t.add(0, 100, 1.0);
        const std::size_t a = t.add(1, 30, 2.0, {a0, a1});
        const std::size_t b = t.add(1, 30, 1.0, {b0, b1});
        const std::size_t r = t.root(2, 10, 1.0, {a, b});
        LevelChoice c = t.choose(100, LodPolicy::Uniform);
        QCOMPARE(sorted(c.shown), sorted({a, b}));
        QCOMPARE(c.bytes, std::size_t(60));
        QVERIFY(!c.coarsened.empty());
        c = t.choose(100, LodPolicy::PerBrick);
        QCOMPARE(sorted(c.shown), sorted({a0, a1, b}));
        QCOMPARE(c.bytes, std::size_t(60));
        // Level 1 (60) does not fit 59: the root alone.
        c = t.choose(59, LodPolicy::Uniform);
        QCOMPARE(c.shown, std::vector<std::size_t>{r});
        QCOMPARE(c.bytes, std::size_t(10));
        c = t.choose(230, LodPolicy::Uniform);
        QCOMPARE(sorted(c.shown), sorted({a0, a1, b0, b1}));
        QVERIFY(c.coarsened.empty());
    }

    // Random octrees: the shown nodes cover every root once, their bytes add
    // up within the budget; Uniform shows one level, the finest that fits;
    // PerBrick (where refining never frees bytes) leaves no refinement that fits.
    void randomTreesAreCoveredOnce() {
        std::mt19937 rng(11);
        for (int n = 0; n < 200; ++n) {
            Tree t;
            const bool monotone = n % 2 == 0;
            const int levels = 1 + n % 4;
            const int rootCount = 1 + n % 5;
            for (int r = 0; r < rootCount; ++r) {
                t.roots.push_back(grow(t, levels - 1, 4, rng, monotone));
            }
            std::vector<std::size_t> perLevel(std::size_t(levels), 0);
            for (const LodNode& node : t.nodes) {
                perLevel[std::size_t(node.level)] += node.bytes;
            }
            const std::size_t coarse = perLevel.back(), fine = perLevel.front();
            std::uniform_int_distribution<std::size_t> pick(coarse, std::max(coarse, fine) + 50);
            const std::size_t budget = pick(rng);
            for (const LodPolicy p : {LodPolicy::PerBrick, LodPolicy::Uniform}) {
                const LevelChoice c = t.choose(budget, p);
                checkCover(t, c.shown);
                QCOMPARE(c.bytes, bytesOf(t, c.shown));
                QVERIFY(c.bytes <= budget);
                QCOMPARE(c.coarsened.empty(), fine <= budget);
                if (fine <= budget) {
                    for (const std::size_t s : c.shown) {
                        QCOMPARE(t.nodes[s].level, 0);
                    }
                }
                if (p == LodPolicy::Uniform) {
                    const int level = t.nodes[c.shown.front()].level;
                    for (const std::size_t s : c.shown) {
                        QCOMPARE(t.nodes[s].level, level);
                    }
                    QCOMPARE(c.bytes, perLevel[std::size_t(level)]);
                    for (int finer = 0; finer < level; ++finer) {
                        QVERIFY(perLevel[std::size_t(finer)] > budget);
                    }
                } else if (monotone) {
                    for (const std::size_t s : c.shown) {
                        if (t.nodes[s].level == 0) {
                            continue;
                        }
                        std::size_t children = 0;
                        for (const std::size_t k : t.nodes[s].children) {
                            children += t.nodes[k].bytes;
                        }
                        QVERIFY2(c.bytes - t.nodes[s].bytes + children > budget,
                                 qPrintable(QString("tree %1: node %2 refines within the budget")
                                                .arg(n)
                                                .arg(s)));
                    }
                }
            }
        }
    }
};

QTEST_GUILESS_MAIN(TestBrickLevels)
#include "test_brick_levels.moc"
