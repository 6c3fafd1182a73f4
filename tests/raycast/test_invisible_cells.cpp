// InvisibleCells against its definition, voxel by voxel: the cells whose eight
// voxels all lie below lo or all above hi, none on the last voxel of an axis.
#include <QTest>

#include <array>
#include <random>

#include "core/raycast/InvisibleCells.h"
#include "tests/raycast/RaycastScenes.h"

using namespace lucent;
using namespace lucent::test;

class TestInvisibleCells : public QObject {
    Q_OBJECT
private slots:
    void cellsAreThoseWhoseVoxelsAllLieOutside_data() {
        QTest::addColumn<int>("type");
        QTest::newRow("int16") << int(VoxelType::Int16);
        QTest::newRow("uint16") << int(VoxelType::UInt16);
        QTest::newRow("float") << int(VoxelType::Float32);
    }
    void cellsAreThoseWhoseVoxelsAllLieOutside() {
        QFETCH(int, type);
        std::mt19937 rng(11);
        // Odd sizes: rows that end inside a word, and rows of more than one word.
        for (const glm::ivec3 dims : {glm::ivec3(37, 9, 7), glm::ivec3(70, 5, 4),
                                      glm::ivec3(3, 3, 3), glm::ivec3(64, 4, 5)}) {
            // Clustered values (runs of one level) so that whole cells share a side.
            std::uniform_int_distribution<int> level(0, 3);
            std::vector<double> levels(std::size_t(dims.x) * dims.y * dims.z);
            for (double& l : levels) {
                l = std::array{10.0, 100.0, 100.5, 900.0}[std::size_t(level(rng))];
            }
            const Volume v = makeVolume(
                dims,
                [&](int i, int j, int k) {
                    return levels[std::size_t(i / 3 + dims.x * (j / 2 + dims.y * k))];
                },
                VoxelType(type));
            for (const auto& [lo, hi] :
                 {std::pair(100.0, 100.5), std::pair(99.5, 100.2), std::pair(-1e9, 500.0),
                  std::pair(50.0, 1e9), std::pair(-1e9, 1e9), std::pair(1e9, 2e9)}) {
                const InvisibleCells cells = findInvisibleCells(v, lo, hi);
                int set = 0;
                for (int k = 0; k < dims.z; ++k) {
                    for (int j = 0; j < dims.y; ++j) {
                        for (int i = 0; i < dims.x; ++i) {
                            bool below = true, above = true;
                            for (int c = 0; c < 8; ++c) {
                                const glm::ivec3 p(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2));
                                const double x = p.x < dims.x && p.y < dims.y && p.z < dims.z
                                                     ? v.value(p.x, p.y, p.z)
                                                     : 0.0;
                                below = below && x < lo;
                                above = above && x > hi;
                            }
                            const bool inner = i < dims.x - 2 && j < dims.y - 2 && k < dims.z - 2;
                            const bool expected = inner && (below || above);
                            set += expected ? 1 : 0;
                            if (cells.contains({i, j, k}) != expected) {
                                QFAIL(qPrintable(QString("cell %1 %2 %3 of %4x%5x%6, bounds %7 %8")
                                                     .arg(i)
                                                     .arg(j)
                                                     .arg(k)
                                                     .arg(dims.x)
                                                     .arg(dims.y)
                                                     .arg(dims.z)
                                                     .arg(lo)
                                                     .arg(hi)));
                            }
                        }
                    }
                }
                // The bounds that leave nothing visible mark every inner cell.
                if (lo > 1e8) {
                    QCOMPARE(set, (dims.x - 2) * (dims.y - 2) * (dims.z - 2));
                }
            }
        }
    }
};

QTEST_APPLESS_MAIN(TestInvisibleCells)
#include "test_invisible_cells.moc"
