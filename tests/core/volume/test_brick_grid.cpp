// BrickGrid and visibleBricks against brute force: brick counts and ranges,
// min/max over core plus overlap for every voxel type, and the set of bricks
// a transfer function threshold and a clip box leave.
#include <QTest>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "core/volume/BlockRanges.h"
#include "core/volume/BrickGrid.h"

using namespace lucent;

namespace {

Volume randomVolume(glm::ivec3 dims, VoxelType type, unsigned seed) {
    VolumeGeometry g;
    g.dims = dims;
    Volume volume(g, type);
    std::mt19937 rng(seed);
    visitVoxels(volume, [&](auto voxels) {
        using T = typename decltype(voxels)::value_type;
        if constexpr (std::is_floating_point_v<T>) {
            std::uniform_real_distribution<float> d(-1500.0f, 3000.0f);
            for (auto& v : voxels) {
                v = d(rng);
            }
        } else {
            std::uniform_int_distribution<int> d(std::numeric_limits<T>::min(),
                                                 std::numeric_limits<T>::max());
            for (auto& v : voxels) {
                v = static_cast<T>(d(rng));
            }
        }
    });
    return volume;
}

struct Range {
    float lo = std::numeric_limits<float>::infinity();
    float hi = -std::numeric_limits<float>::infinity();
};

// Min/max over [first - overlap, last + overlap) clamped to the volume.
Range bruteRange(const Volume& v, const Brick& b, int overlap) {
    Range r;
    const glm::ivec3 lo = glm::max(b.first - overlap, glm::ivec3(0));
    const glm::ivec3 hi = glm::min(b.last + overlap, v.dims());
    for (int k = lo.z; k < hi.z; ++k) {
        for (int j = lo.y; j < hi.y; ++j) {
            for (int i = lo.x; i < hi.x; ++i) {
                const auto x = static_cast<float>(v.value(i, j, k));
                r.lo = std::min(r.lo, x);
                r.hi = std::max(r.hi, x);
            }
        }
    }
    return r;
}

void checkAgainstBruteForce(const Volume& volume, int size, int overlap) {
    const BrickGrid grid(volume, size, overlap);
    const glm::ivec3 d = volume.dims();
    const glm::ivec3 n = grid.bricksPerAxis();
    QCOMPARE(grid.count(), std::size_t(n.x) * n.y * n.z);
    for (const Brick& b : grid.bricks()) {
        const Range r = bruteRange(volume, b, overlap);
        if (b.minValue != r.lo || b.maxValue != r.hi) {
            QFAIL(qPrintable(QString("dims %1x%2x%3 size %4 overlap %5 brick (%6,%7,%8): "
                                     "[%9, %10] instead of [%11, %12]")
                                 .arg(d.x)
                                 .arg(d.y)
                                 .arg(d.z)
                                 .arg(size)
                                 .arg(overlap)
                                 .arg(b.index.x)
                                 .arg(b.index.y)
                                 .arg(b.index.z)
                                 .arg(b.minValue)
                                 .arg(b.maxValue)
                                 .arg(r.lo)
                                 .arg(r.hi)));
        }
        QCOMPARE(grid.paddedFirst(b), glm::max(b.first - overlap, glm::ivec3(0)));
        QCOMPARE(grid.paddedLast(b), glm::min(b.last + overlap, d));
    }
}

} // namespace

class TestBrickGrid : public QObject {
    Q_OBJECT
private slots:
    void bricksPerAxisAndRanges_data() {
        QTest::addColumn<int>("dx");
        QTest::addColumn<int>("dy");
        QTest::addColumn<int>("dz");
        QTest::addColumn<int>("size");
        QTest::addRow("one brick") << 64 << 64 << 64 << 64;
        QTest::addRow("divisible") << 128 << 64 << 32 << 32;
        QTest::addRow("not divisible") << 130 << 65 << 7 << 64;
        QTest::addRow("odd dims, 16") << 100 << 50 << 17 << 16;
        QTest::addRow("size 1") << 3 << 4 << 5 << 1;
        QTest::addRow("size larger than volume") << 10 << 20 << 30 << 64;
        QTest::addRow("one slice") << 40 << 33 << 1 << 8;
    }
    void bricksPerAxisAndRanges() {
        QFETCH(int, dx);
        QFETCH(int, dy);
        QFETCH(int, dz);
        QFETCH(int, size);
        const glm::ivec3 dims(dx, dy, dz);
        const Volume volume = randomVolume(dims, VoxelType::Int16, 1);
        const BrickGrid grid(volume, size, 3);
        QCOMPARE(grid.brickSize(), size);
        QCOMPARE(grid.overlap(), 3);
        const glm::ivec3 n = grid.bricksPerAxis();
        for (int a = 0; a < 3; ++a) {
            QCOMPARE(n[a], (dims[a] + size - 1) / size);
        }
        std::size_t voxels = 0;
        for (std::size_t id = 0; id < grid.count(); ++id) {
            const Brick& b = grid.bricks()[id];
            QCOMPARE(&grid.brickAt(b.index), &b);
            QCOMPARE(grid.idOf(b.index), static_cast<std::uint32_t>(id));
            QCOMPARE(b.first, b.index * size);
            for (int a = 0; a < 3; ++a) {
                // Full size inside, smaller only at the far edge of each axis.
                const int want = b.index[a] + 1 < n[a] ? size : dims[a] - (n[a] - 1) * size;
                QCOMPARE(b.last[a] - b.first[a], want);
                QVERIFY(want >= 1 && want <= size);
            }
            const glm::ivec3 e = b.last - b.first;
            voxels += std::size_t(e.x) * e.y * e.z;
        }
        QCOMPARE(voxels, volume.geometry().voxelCount()); // cores tile the volume
        QVERIFY(grid.bricks().front().index == glm::ivec3(0));
        QVERIFY(grid.bricks().back().last == dims);
    }

    void minMaxMatchesBruteForce_data() {
        QTest::addColumn<int>("type");
        QTest::addRow("int16") << int(VoxelType::Int16);
        QTest::addRow("uint16") << int(VoxelType::UInt16);
        QTest::addRow("float32") << int(VoxelType::Float32);
    }
    void minMaxMatchesBruteForce() {
        QFETCH(int, type);
        unsigned seed = 10;
        for (const glm::ivec3 dims : {glm::ivec3(37, 29, 21), glm::ivec3(64, 16, 9),
                                      glm::ivec3(40, 40, 40), glm::ivec3(5, 1, 3)}) {
            const Volume volume = randomVolume(dims, VoxelType(type), seed++);
            for (const auto& [size, overlap] :
                 {std::pair{8, 3}, std::pair{16, 0}, std::pair{7, 1}, std::pair{4, 6},
                  std::pair{2, 3}, std::pair{64, 3}, std::pair{1, 1}}) {
                checkAgainstBruteForce(volume, size, overlap);
                if (QTest::currentTestFailed()) {
                    return;
                }
            }
        }
    }

    void localFeatureReachesNeighboursThroughTheOverlapOnly() {
        VolumeGeometry g;
        g.dims = {32, 16, 16};
        Volume volume(g, VoxelType::UInt16);
        std::fill(volume.voxels<std::uint16_t>().begin(), volume.voxels<std::uint16_t>().end(), 0);
        volume.voxels<std::uint16_t>()[volume.linearIndex(17, 5, 5)] = 1000; // in brick x = 1
        const BrickGrid grid(volume, 16, 3);
        QCOMPARE(grid.brickAt({1, 0, 0}).maxValue, 1000.0f);
        QCOMPARE(grid.brickAt({0, 0, 0}).maxValue, 1000.0f); // 17 < 16 + 3
        const BrickGrid tight(volume, 16, 1);
        QCOMPARE(tight.brickAt({0, 0, 0}).maxValue, 0.0f); // 17 >= 16 + 1
        QCOMPARE(tight.brickAt({0, 0, 0}).minValue, 0.0f);
    }

    void nanVoxelsAreIgnored() {
        VolumeGeometry g;
        g.dims = {8, 8, 8};
        Volume volume(g, VoxelType::Float32);
        auto v = volume.voxels<float>();
        for (std::size_t i = 0; i < v.size(); ++i) {
            v[i] = static_cast<float>(i);
        }
        v[0] = std::numeric_limits<float>::quiet_NaN();
        const BrickGrid grid(volume, 8, 3);
        QCOMPARE(grid.bricks()[0].minValue, 1.0f);
        QCOMPARE(grid.bricks()[0].maxValue, 511.0f);
    }

    // Every trilinear sample in a block, odd dimensions included, lies in its
    // block's range; a NaN voxel opens the range of each block that reads it.
    void blockRangesHoldEverySampleInTheBlock() {
        Volume volume = randomVolume({9, 6, 7}, VoxelType::Float32, 5);
        const BlockRanges ranges(volume);
        QCOMPARE(ranges.blocksPerAxis(), glm::ivec3(5, 3, 4));
        std::mt19937 rng(9);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        const glm::ivec3 d = volume.dims();
        for (int trial = 0; trial < 4000; ++trial) {
            const glm::dvec3 p = glm::dvec3(unit(rng), unit(rng), unit(rng)) * glm::dvec3(d - 1);
            const glm::ivec3 b = glm::min(glm::ivec3(p / 2.0), ranges.blocksPerAxis() - 1);
            const glm::ivec3 i = glm::min(glm::ivec3(p), d - 2);
            const glm::dvec3 f = p - glm::dvec3(i);
            double v = 0.0;
            for (int n = 0; n < 8; ++n) {
                const glm::ivec3 o(n & 1, (n >> 1) & 1, n >> 2);
                const double w =
                    (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
                v += w * volume.value(i.x + o.x, i.y + o.y, i.z + o.z);
            }
            const std::size_t id = ranges.idOf(b);
            QVERIFY(!ranges.outside(id, float(v - 1e-3), float(v + 1e-3)));
        }
        volume.voxels<float>()[volume.linearIndex(2, 2, 2)] =
            std::numeric_limits<float>::quiet_NaN();
        const BlockRanges withNan(volume);
        for (const glm::ivec3 b : {glm::ivec3(0, 0, 0), glm::ivec3(1, 1, 1), glm::ivec3(0, 1, 0)}) {
            QVERIFY(!withNan.outside(withNan.idOf(b), 1e30f, -1e30f));
        }
        QVERIFY(withNan.outside(withNan.idOf({3, 2, 3}), 1e30f, 2e30f));
    }

    void visibleBricksMatchBruteForce() {
        const Volume volume = randomVolume({50, 41, 30}, VoxelType::Float32, 3);
        for (const auto& [size, overlap] : {std::pair{8, 3}, std::pair{16, 1}, std::pair{5, 0}}) {
            const BrickGrid grid(volume, size, overlap);
            for (const double threshold : {-2000.0, 2990.0, 2999.0, 5000.0}) {
                const auto isVisible = [threshold](double, double hi) { return hi >= threshold; };
                for (const ClipBox& clip :
                     {ClipBox{}, ClipBox{{10.0, 3.5, -4.0}, {20.2, 30.0, 12.0}},
                      ClipBox{{7.5, 7.5, 7.5}, {7.5, 7.5, 7.5}},
                      ClipBox{{30.0, 0.0, 0.0}, {20.0, 40.0, 29.0}}}) {
                    std::vector<std::uint32_t> want;
                    for (std::uint32_t id = 0; id < grid.count(); ++id) {
                        const Brick& b = grid.bricks()[id];
                        const Range r = bruteRange(volume, b, overlap);
                        const glm::ivec3 lo = glm::max(b.first - overlap, glm::ivec3(0));
                        const glm::ivec3 hi = glm::min(b.last + overlap, volume.dims()) - 1;
                        bool meets = true;
                        for (int a = 0; a < 3; ++a) {
                            meets = meets && clip.lo[a] <= hi[a] && clip.hi[a] >= lo[a];
                        }
                        if (meets && r.hi >= threshold) {
                            want.push_back(id);
                        }
                    }
                    QCOMPARE(visibleBricks(grid, isVisible, clip), want);
                }
            }
            QCOMPARE(visibleBricks(
                         grid, [](double, double) { return true; }, ClipBox{})
                         .size(),
                     grid.count());
            QVERIFY(visibleBricks(
                        grid, [](double, double) { return false; }, ClipBox{})
                        .empty());
        }
    }

    void badArguments() {
        const Volume volume = randomVolume({4, 4, 4}, VoxelType::Int16, 4);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, BrickGrid(volume, 0));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, BrickGrid(volume, -5));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, BrickGrid(volume, 8, -1));
        const BrickGrid grid(volume, 2, 3);
        QVERIFY_THROWS_EXCEPTION(std::out_of_range, grid.brickAt({2, 0, 0}));
        QVERIFY_THROWS_EXCEPTION(std::out_of_range, grid.brickAt({0, -1, 0}));
        const BrickGrid empty(Volume{}, 64, 3);
        QCOMPARE(empty.count(), std::size_t(0));
        QCOMPARE(empty.bricksPerAxis(), glm::ivec3(0));
        QVERIFY(visibleBricks(
                    empty, [](double, double) { return true; }, ClipBox{})
                    .empty());
    }
};

QTEST_APPLESS_MAIN(TestBrickGrid)
#include "test_brick_grid.moc"
