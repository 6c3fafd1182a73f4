// BoxAtlas, the guillotine allocator of the GPU brick pool: placed boxes stay
// inside the extent and never overlap, released room is reused, the used
// texels add up, and extentFor sizes an atlas for a set of boxes.
#include <QTest>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/volume/BoxAtlas.h"

using namespace lucent;

namespace {

struct Placed {
    glm::ivec3 origin, size;
};

std::size_t volumeOf(glm::ivec3 s) {
    return std::size_t(s.x) * std::size_t(s.y) * std::size_t(s.z);
}

bool overlap(const Placed& a, const Placed& b) {
    return glm::all(glm::lessThan(a.origin, b.origin + b.size)) &&
           glm::all(glm::lessThan(b.origin, a.origin + a.size));
}

bool inside(const Placed& p, glm::ivec3 extent) {
    return glm::all(glm::greaterThanEqual(p.origin, glm::ivec3(0))) &&
           glm::all(glm::lessThanEqual(p.origin + p.size, extent));
}

// Every box inside the extent, no two sharing a texel, and usedTexels their sum.
void checkPlacement(const BoxAtlas& atlas, const std::vector<Placed>& placed) {
    std::size_t used = 0;
    for (std::size_t a = 0; a < placed.size(); ++a) {
        QVERIFY2(inside(placed[a], atlas.extent()), qPrintable(QString("box %1").arg(a)));
        used += volumeOf(placed[a].size);
        for (std::size_t b = a + 1; b < placed.size(); ++b) {
            QVERIFY2(!overlap(placed[a], placed[b]),
                     qPrintable(QString("boxes %1, %2").arg(a).arg(b)));
        }
    }
    QCOMPARE(atlas.usedTexels(), used);
}

} // namespace

class TestBoxAtlas : public QObject {
    Q_OBJECT

private slots:
    void overlapHelperSeesOverlaps() {
        // The check below must be able to fail.
        QVERIFY(overlap({{0, 0, 0}, {4, 4, 4}}, {{3, 3, 3}, {2, 2, 2}}));
        QVERIFY(!overlap({{0, 0, 0}, {4, 4, 4}}, {{4, 0, 0}, {2, 2, 2}}));
        QVERIFY(!inside({{30, 0, 0}, {4, 4, 4}}, glm::ivec3(32)));
    }

    // Random boxes until the atlas is full, then random releases and more
    // boxes: never outside the extent, never overlapping.
    void randomBoxesNeverOverlap() {
        for (unsigned seed = 1; seed <= 5; ++seed) {
            std::mt19937 rng(seed);
            std::uniform_int_distribution<int> side(1, 17);
            const glm::ivec3 extent(64, 48, 40 + int(seed));
            BoxAtlas atlas(extent);
            QCOMPARE(atlas.extent(), extent);
            QCOMPARE(atlas.texels(), volumeOf(extent));
            std::vector<Placed> placed;
            int refused = 0;
            for (int round = 0; round < 4; ++round) {
                for (int n = 0; n < 400 && refused < 40; ++n) {
                    const glm::ivec3 size(side(rng), side(rng), side(rng));
                    if (const auto o = atlas.place(size)) {
                        placed.push_back({*o, size});
                    } else {
                        ++refused;
                    }
                }
                checkPlacement(atlas, placed);
                // Boxes of up to 17 fill a fair share of a fresh atlas before
                // 40 refusals.
                QVERIFY2(round > 0 || atlas.usedTexels() * 3 > atlas.texels(),
                         qPrintable(QString("%1 of %2 texels used")
                                        .arg(atlas.usedTexels())
                                        .arg(atlas.texels())));
                // A half of them (at random) back.
                std::shuffle(placed.begin(), placed.end(), rng);
                const std::size_t keep = placed.size() / 2;
                for (std::size_t n = keep; n < placed.size(); ++n) {
                    atlas.release(placed[n].origin, placed[n].size);
                }
                placed.resize(keep);
                checkPlacement(atlas, placed);
                refused = 0;
            }
        }
    }

    void boxesOfOneSizeTileTheAtlas() {
        BoxAtlas atlas({32, 16, 16});
        std::vector<Placed> placed;
        for (int n = 0; n < 16; ++n) {
            const auto o = atlas.place(glm::ivec3(8));
            QVERIFY2(o.has_value(), qPrintable(QString("box %1").arg(n)));
            placed.push_back({*o, glm::ivec3(8)});
        }
        checkPlacement(atlas, placed);
        QCOMPARE(atlas.usedTexels(), atlas.texels());
        QVERIFY(!atlas.place(glm::ivec3(1)));
    }

    void tooLargeABoxIsRefused() {
        BoxAtlas atlas({8, 8, 8});
        QVERIFY(!atlas.place({9, 1, 1}));
        QVERIFY(!atlas.place({1, 1, 9}));
        QCOMPARE(atlas.usedTexels(), std::size_t(0));
        // 4 x 8 x 8 fits; another 5 x 1 x 1 does not fit the 4 x 8 x 8 left,
        // though there are texels enough.
        const auto a = atlas.place({4, 8, 8});
        QVERIFY(a.has_value());
        QVERIFY(!atlas.place({5, 1, 1}));
        const auto b = atlas.place({4, 8, 8});
        QVERIFY(b.has_value());
        QVERIFY(*a != *b);
        QVERIFY(!atlas.place({1, 1, 1}));
        QCOMPARE(atlas.usedTexels(), std::size_t(512));
    }

    void releasedRoomIsReused() {
        BoxAtlas atlas({8, 8, 8});
        QCOMPARE(atlas.place(glm::ivec3(8)), std::optional<glm::ivec3>(glm::ivec3(0)));
        atlas.release(glm::ivec3(0), glm::ivec3(8));
        QCOMPARE(atlas.usedTexels(), std::size_t(0));
        QCOMPARE(atlas.place(glm::ivec3(8)), std::optional<glm::ivec3>(glm::ivec3(0)));
        atlas.release(glm::ivec3(0), glm::ivec3(8));

        // Full of eight 4^3 boxes: a released one is the only room there is.
        std::vector<glm::ivec3> at;
        for (int n = 0; n < 8; ++n) {
            const auto o = atlas.place(glm::ivec3(4));
            QVERIFY(o.has_value());
            at.push_back(*o);
        }
        QVERIFY(!atlas.place(glm::ivec3(1)));
        atlas.release(at[5], glm::ivec3(4));
        QCOMPARE(atlas.usedTexels(), std::size_t(7 * 64));
        QVERIFY(!atlas.place(glm::ivec3(5)));
        QCOMPARE(atlas.place(glm::ivec3(4)), std::optional<glm::ivec3>(at[5]));
        QCOMPARE(atlas.usedTexels(), std::size_t(8 * 64));
        // Smaller boxes go into released room too, and only there.
        atlas.release(at[2], glm::ivec3(4));
        std::vector<Placed> placed;
        for (int n = 0; n < 8; ++n) {
            if (n != 2) {
                placed.push_back({at[std::size_t(n)], glm::ivec3(4)});
            }
        }
        for (int n = 0; n < 8; ++n) {
            const auto o = atlas.place(glm::ivec3(2));
            QVERIFY(o.has_value());
            QVERIFY(glm::all(glm::greaterThanEqual(*o, at[2])) &&
                    glm::all(glm::lessThanEqual(*o + 2, at[2] + 4)));
            placed.push_back({*o, glm::ivec3(2)});
        }
        QVERIFY(!atlas.place(glm::ivec3(1)));
        checkPlacement(atlas, placed);
    }

    void usedTexelsFollowPlacesAndReleases() {
        BoxAtlas atlas({20, 10, 5});
        QCOMPARE(atlas.texels(), std::size_t(1000));
        const auto a = atlas.place({3, 4, 5});
        const auto b = atlas.place({7, 1, 2});
        QVERIFY(a && b);
        QCOMPARE(atlas.usedTexels(), std::size_t(60 + 14));
        QVERIFY(!atlas.place({1, 1, 6}));
        QCOMPARE(atlas.usedTexels(), std::size_t(74)); // a refusal takes nothing
        atlas.release(*a, {3, 4, 5});
        QCOMPARE(atlas.usedTexels(), std::size_t(14));
        atlas.release(*b, {7, 1, 2});
        QCOMPARE(atlas.usedTexels(), std::size_t(0));
    }

    void invalidSizesThrow() {
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, BoxAtlas({0, 8, 8}));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, BoxAtlas({8, 8, -1}));
        BoxAtlas atlas({8, 8, 8});
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, atlas.place({0, 1, 1}));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, atlas.place({1, -2, 1}));
        QCOMPARE(atlas.usedTexels(), std::size_t(0));
        QVERIFY(atlas.place(glm::ivec3(8)).has_value()); // nothing was taken
    }

    // x and y whole multiples of the largest box side (where maxSide does not
    // cap them), about the cube root of the texels; the extent holds them all.
    void extentForHoldsTheTexels() {
        struct Case {
            std::size_t texels;
            glm::ivec3 largest;
            int maxSide;
        };
        const Case cases[] = {
            {1000 * 16 * 16 * 16, glm::ivec3(16), 2048}, // 160^3
            {10 * 16 * 16 * 16, glm::ivec3(16), 2048},
            {123457, {12, 20, 8}, 2048},
            {5, glm::ivec3(9), 2048}, // one box bigger than the texels
            {1, glm::ivec3(1), 1},
            {120 * 120 * 120, glm::ivec3(32), 128}, // capped by maxSide: 128 x 128
            {3000000, {30, 10, 60}, 512},
        };
        for (const Case& c : cases) {
            const glm::ivec3 e = BoxAtlas::extentFor(c.texels, c.largest, c.maxSide);
            const QString at =
                QString("%1 texels, (%2 %3 %4)").arg(c.texels).arg(e.x).arg(e.y).arg(e.z);
            QVERIFY2(volumeOf(e) >= c.texels, qPrintable(at));
            QVERIFY2(glm::all(glm::greaterThanEqual(e, c.largest)), qPrintable(at));
            QVERIFY2(glm::all(glm::lessThanEqual(e, glm::ivec3(c.maxSide))), qPrintable(at));
            const int unit = std::max(c.largest.x, c.largest.y);
            QVERIFY2(e.x % unit == 0 && e.y % unit == 0, qPrintable(at));
        }
        // A cube of whole boxes where it comes out even.
        QCOMPARE(BoxAtlas::extentFor(1000 * 16 * 16 * 16, glm::ivec3(16), 2048), glm::ivec3(160));
        QCOMPARE(BoxAtlas::extentFor(64 * 8 * 8 * 8, glm::ivec3(8), 2048), glm::ivec3(32));
        // About the cube root: not a slab of one box's depth.
        const glm::ivec3 e = BoxAtlas::extentFor(100 * 16 * 16 * 16, glm::ivec3(16), 2048);
        const double root = std::cbrt(100.0 * 16 * 16 * 16);
        QVERIFY(std::abs(e.x - root) <= 16.0 && std::abs(e.y - root) <= 16.0);
        QVERIFY(e.z >= 16 && std::abs(e.z - root) <= 2 * 16.0);
        // A capped side (maxSide is no multiple of the box): every side within it.
        const glm::ivec3 capped = BoxAtlas::extentFor(99 * 99 * 99, glm::ivec3(16), 100);
        QVERIFY(glm::all(glm::lessThanEqual(capped, glm::ivec3(100))));
        QVERIFY(volumeOf(capped) >= std::size_t(99 * 99 * 99));
        // Exactly maxSide^3 still fits.
        QCOMPARE(BoxAtlas::extentFor(64 * 64 * 64, glm::ivec3(16), 64), glm::ivec3(64));
    }

    void extentForThrowsWhenMaxSideIsTooSmall() {
        QVERIFY_THROWS_EXCEPTION(std::length_error,
                                 BoxAtlas::extentFor(64 * 64 * 64 + 1, glm::ivec3(16), 64));
        QVERIFY_THROWS_EXCEPTION(std::length_error,
                                 BoxAtlas::extentFor(101 * 101 * 101, glm::ivec3(8), 100));
        // A single box larger than a side.
        QVERIFY_THROWS_EXCEPTION(std::length_error, BoxAtlas::extentFor(1000, {65, 1, 1}, 64));
        QVERIFY_THROWS_EXCEPTION(std::length_error, BoxAtlas::extentFor(1000, {1, 1, 65}, 64));
    }

    // maxTexels caps the extent where the largest box still fits: z first,
    // then x and y by whole boxes.
    void extentForStaysWithinMaxTexels() {
        const glm::ivec3 box(16);
        const std::size_t texels = 1000 * 16 * 16 * 16; // 160^3 without a cap
        // Room for 24 layers of 160 x 160: only z shrinks.
        QCOMPARE(BoxAtlas::extentFor(texels, box, 2048, 160 * 160 * 24 + 100),
                 glm::ivec3(160, 160, 24));
        // Not even 16 layers of 160 x 160: x and y shrink too, by whole boxes.
        for (const std::size_t cap :
             {std::size_t(160 * 160 * 10), std::size_t(20000), std::size_t(16 * 16 * 16)}) {
            const glm::ivec3 e = BoxAtlas::extentFor(texels, box, 2048, cap);
            const QString at = QString("cap %1: (%2 %3 %4)").arg(cap).arg(e.x).arg(e.y).arg(e.z);
            QVERIFY2(volumeOf(e) <= cap, qPrintable(at));
            QVERIFY2(glm::all(glm::greaterThanEqual(e, box)), qPrintable(at));
            QVERIFY2(e.x % 16 == 0 && e.y % 16 == 0, qPrintable(at));
        }
        QCOMPARE(BoxAtlas::extentFor(texels, box, 2048, 16 * 16 * 16), box);
        // A cap above what is needed changes nothing.
        QCOMPARE(BoxAtlas::extentFor(texels, box, 2048, 2 * texels), glm::ivec3(160));
    }

    // What extentFor gives is an atlas: equal boxes filling whole layers all fit.
    void extentForMakesAnAtlasForEqualBoxes() {
        const glm::ivec3 box(16, 16, 16);
        const std::size_t count = 64;
        const glm::ivec3 e = BoxAtlas::extentFor(count * volumeOf(box), box, 2048);
        BoxAtlas atlas(e);
        std::vector<Placed> placed;
        for (std::size_t n = 0; n < count; ++n) {
            const auto o = atlas.place(box);
            QVERIFY2(o.has_value(), qPrintable(QString("box %1 of %2").arg(n).arg(count)));
            placed.push_back({*o, box});
        }
        checkPlacement(atlas, placed);
    }
};

QTEST_GUILESS_MAIN(TestBoxAtlas)
#include "test_box_atlas.moc"
