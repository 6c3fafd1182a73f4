// InvisibleCells against its definition, cell by cell: the cells whose eight
// voxels all lie below lo or all above hi (none on the last voxel of an axis),
// and how many cells around them are such cells too.
#include <QTest>

#include <array>
#include <random>

#include "core/raycast/InvisibleCells.h"
#include "tests/core/raycast/RaycastScenes.h"

using namespace lucent;
using namespace lucent::test;

class TestInvisibleCells : public QObject {
    Q_OBJECT
private slots:
    void clearanceIsTheDistanceToWhatMayBeSeen_data() {
        QTest::addColumn<int>("type");
        QTest::newRow("int16") << int(VoxelType::Int16);
        QTest::newRow("uint16") << int(VoxelType::UInt16);
        QTest::newRow("float") << int(VoxelType::Float32);
    }
    void clearanceIsTheDistanceToWhatMayBeSeen() {
        QFETCH(int, type);
        std::mt19937 rng(11);
        int levels[4] = {};
        // Odd sizes: rows that end inside a word, rows of several words.
        for (const glm::ivec3 dims : {glm::ivec3(37, 9, 7), glm::ivec3(70, 12, 9),
                                      glm::ivec3(3, 3, 3), glm::ivec3(130, 9, 8)}) {
            // Clustered values (runs of one level) so that whole regions share a side.
            std::uniform_int_distribution<int> level(0, 3);
            std::vector<double> values(std::size_t(dims.x) * dims.y * dims.z);
            for (double& l : values) {
                l = std::array{10.0, 100.0, 100.5, 900.0}[std::size_t(level(rng))];
            }
            const Volume v = makeVolume(
                dims,
                [&](int i, int j, int k) {
                    return values[std::size_t(i / 5 + dims.x * (j / 3 + dims.y * (k / 2)))];
                },
                VoxelType(type));
            auto at = [&](glm::ivec3 c) {
                return std::size_t(c.x) + std::size_t(dims.x) * (c.y + std::size_t(dims.y) * c.z);
            };
            for (const auto& [lo, hi] :
                 {std::pair(100.0, 100.5), std::pair(99.5, 100.2), std::pair(-1e9, 500.0),
                  std::pair(50.0, 1e9), std::pair(-1e9, 1e9), std::pair(1e9, 2e9)}) {
                // Brute force: the cells whose eight voxels all lie on one side.
                std::vector<bool> clear(values.size(), false);
                for (int k = 0; k + 2 < dims.z; ++k) {
                    for (int j = 0; j + 2 < dims.y; ++j) {
                        for (int i = 0; i + 2 < dims.x; ++i) {
                            bool below = true, above = true;
                            for (int c = 0; c < 8; ++c) {
                                const double x =
                                    v.value(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2));
                                below = below && x < lo;
                                above = above && x > hi;
                            }
                            clear[at({i, j, k})] = below || above;
                        }
                    }
                }
                // Within r cells of c, all clear (cells beyond the volume are not).
                auto around = [&](glm::ivec3 c, int r) {
                    for (int dz = -r; dz <= r; ++dz) {
                        for (int dy = -r; dy <= r; ++dy) {
                            for (int dx = -r; dx <= r; ++dx) {
                                const glm::ivec3 p = c + glm::ivec3(dx, dy, dz);
                                if (glm::any(glm::lessThan(p, glm::ivec3(0))) ||
                                    glm::any(glm::greaterThanEqual(p, dims)) || !clear[at(p)]) {
                                    return false;
                                }
                            }
                        }
                    }
                    return true;
                };
                const InvisibleCells cells = findInvisibleCells(v, lo, hi);
                for (int k = 0; k < dims.z; ++k) {
                    for (int j = 0; j < dims.y; ++j) {
                        for (int i = 0; i < dims.x; ++i) {
                            const glm::ivec3 c(i, j, k);
                            const int expected =
                                around(c, 0) ? (around(c, 1) ? (around(c, 2) ? 3 : 2) : 1) : 0;
                            ++levels[expected];
                            if (cells.clearance(c) != expected) {
                                QFAIL(qPrintable(
                                    QString("cell %1 %2 %3 of %4x%5x%6, bounds %7 %8: %9, not %10")
                                        .arg(i)
                                        .arg(j)
                                        .arg(k)
                                        .arg(dims.x)
                                        .arg(dims.y)
                                        .arg(dims.z)
                                        .arg(lo)
                                        .arg(hi)
                                        .arg(cells.clearance(c))
                                        .arg(expected)));
                            }
                        }
                    }
                }
            }
        }
        // Every level occurs, so that each was checked.
        for (const int n : levels) {
            QVERIFY(n > 100);
        }
    }
};

QTEST_APPLESS_MAIN(TestInvisibleCells)
#include "test_invisible_cells.moc"
