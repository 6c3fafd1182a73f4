// Smoothing on pieces of the real 28-slice head CT (0.45 x 0.45 x 5 mm voxels): the median and the
// closing against brute-force references (every window counted, every ball offset tried),
// and the brush and the outline fill against the voxels picked by hand.
#include <QTest>

#include <cmath>

#include "core/io/Catalog.h"
#include "core/segmentation/SegmentBrush.h"
#include "core/segmentation/SegmentEffects.h"
#include "core/segmentation/SegmentSmoothing.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";

// The box [lo, lo + dims) of a mask on its own grid (same spacing).
SegmentMask crop(const SegmentMask& m, const glm::ivec3& lo, const glm::ivec3& dims) {
    SegmentMask out(dims);
    for (int k = 0; k < dims.z; ++k) {
        for (int j = 0; j < dims.y; ++j) {
            for (int i = 0; i < dims.x; ++i) {
                out.set(out.linearIndex(i, j, k), m.at(lo.x + i, lo.y + j, lo.z + k));
            }
        }
    }
    return out;
}

std::vector<glm::ivec3> ballOffsets(const glm::dvec3& spacing, double r) {
    std::vector<glm::ivec3> out;
    const glm::ivec3 reach(glm::ceil(glm::dvec3(r) / spacing));
    for (int k = -reach.z; k <= reach.z; ++k) {
        for (int j = -reach.y; j <= reach.y; ++j) {
            for (int i = -reach.x; i <= reach.x; ++i) {
                const glm::dvec3 d = glm::dvec3(i, j, k) * spacing;
                if (glm::dot(d, d) <= r * r * (1.0 + 1e-9)) {
                    out.push_back({i, j, k});
                }
            }
        }
    }
    return out;
}

} // namespace

class TestSegmentSmoothing : public QObject {
    Q_OBJECT

    Volume ct_;
    SegmentMask bone_;    // a piece of the bone threshold (holes, gaps, specks)
    VolumeGeometry grid_; // its grid

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        ct_ = loadPath(test::kRealData / kCt);
        // The box of the bone threshold with the most bone (holes, gaps and specks there).
        const SegmentMask bone = thresholdMask(ct_, 150.0, 3000.0);
        const glm::ivec3 dims(56, 48, 12);
        glm::ivec3 lo(0);
        std::size_t most = 0;
        for (int y = 0; y + dims.y <= ct_.dims().y; y += 16) {
            for (int x = 0; x + dims.x <= ct_.dims().x; x += 16) {
                const std::size_t n = crop(bone, {x, y, 8}, dims).count();
                if (n > most) {
                    most = n;
                    lo = {x, y, 8};
                }
            }
        }
        bone_ = crop(bone, lo, dims);
        grid_ = ct_.geometry();
        grid_.dims = dims;
        QVERIFY2(bone_.count() > 500 && bone_.count() < bone_.size() / 2,
                 qPrintable(QString::number(bone_.count())));
    }

    void kernelSizesInVoxels() {
        REQUIRE_DATA(kCt);
        // 3 mm: 6.6 voxels of 0.45 mm -> 7; 0.6 of 5 mm -> 1. 12 mm: 26.6 -> 27; 2.4 -> 3.
        QCOMPARE(medianKernelVoxels(grid_, 3.0), glm::ivec3(7, 7, 1));
        QCOMPARE(medianKernelVoxels(grid_, 12.0), glm::ivec3(27, 27, 3));
        QCOMPARE(medianKernelVoxels(grid_, 0.1), glm::ivec3(1, 1, 1));
        QCOMPARE(medianMask(bone_, grid_, 0.1), bone_);
    }

    void medianCountsEveryWindow() {
        REQUIRE_DATA(kCt);
        for (const double mm : {3.0, 12.0}) {
            const glm::ivec3 r = (medianKernelVoxels(grid_, mm) - 1) / 2;
            const SegmentMask got = medianMask(bone_, grid_, mm);
            const glm::ivec3 d = bone_.dims();
            std::size_t differ = 0;
            for (int k = 0; k < d.z; ++k) {
                for (int j = 0; j < d.y; ++j) {
                    for (int i = 0; i < d.x; ++i) {
                        int set = 0, total = 0;
                        for (int c = -r.z; c <= r.z; ++c) {
                            for (int b = -r.y; b <= r.y; ++b) {
                                for (int a = -r.x; a <= r.x; ++a) {
                                    if (bone_.inside({i + a, j + b, k + c})) {
                                        ++total;
                                        set += bone_.at(i + a, j + b, k + c) ? 1 : 0;
                                    }
                                }
                            }
                        }
                        differ += (2 * set > total) != got.at(i, j, k) ? 1 : 0;
                    }
                }
            }
            QCOMPARE(differ, std::size_t{0});
            QVERIFY(got != bone_); // it did smooth something
        }
    }

    void closingTriesEveryBallOffset() {
        REQUIRE_DATA(kCt);
        for (const double r : {2.0, 6.0}) {
            const std::vector<glm::ivec3> ball = ballOffsets(grid_.spacing, r);
            const glm::ivec3 pad = glm::ivec3(glm::ceil(glm::dvec3(r) / grid_.spacing)) + 1;
            const glm::ivec3 d = bone_.dims();
            // Grown: on the grid padded by the reach (nothing set beyond the grid).
            SegmentMask grown(d + 2 * pad);
            for (int k = 0; k < grown.dims().z; ++k) {
                for (int j = 0; j < grown.dims().y; ++j) {
                    for (int i = 0; i < grown.dims().x; ++i) {
                        bool any = false;
                        for (const glm::ivec3& o : ball) {
                            const glm::ivec3 v = glm::ivec3(i, j, k) - pad + o;
                            if (bone_.inside(v) && bone_.at(v.x, v.y, v.z)) {
                                any = true;
                                break;
                            }
                        }
                        grown.set(grown.linearIndex(i, j, k), any);
                    }
                }
            }
            const SegmentMask got = closingMask(bone_, grid_, r);
            std::size_t differ = 0;
            for (int k = 0; k < d.z; ++k) {
                for (int j = 0; j < d.y; ++j) {
                    for (int i = 0; i < d.x; ++i) {
                        bool all = true;
                        for (const glm::ivec3& o : ball) {
                            const glm::ivec3 v = glm::ivec3(i, j, k) + pad + o;
                            all = all && grown.at(v.x, v.y, v.z);
                        }
                        differ += all != got.at(i, j, k) ? 1 : 0;
                    }
                }
            }
            QCOMPARE(differ, std::size_t{0});
            SegmentMask added = got;
            QVERIFY(added.subtract(bone_).any()); // it filled something...
            SegmentMask lost = bone_;
            QVERIFY(!lost.subtract(got).any()); // ...and removed nothing
        }
    }

    void brushAndOutlineByHand() {
        REQUIRE_DATA(kCt);
        const VolumeGeometry& g = ct_.geometry();
        const glm::dvec3 centre = g.toPatient(glm::dvec3(250.3, 260.8, 13.0));
        SegmentMask sphere(g.dims), disc(g.dims);
        const std::size_t painted = paintBrush(sphere, g, centre, 7.5, true);
        const SliceSlab slab{glm::normalize(glm::dvec3(g.direction[2])), 0.5 * g.spacing.z};
        paintBrush(disc, g, centre, 7.5, true, slab);
        std::size_t want = 0, wantDisc = 0;
        for (int k = 0; k < g.dims.z; ++k) {
            for (int j = 230; j < 290; ++j) {
                for (int i = 220; i < 280; ++i) {
                    const glm::dvec3 p = g.toPatient(glm::dvec3(i, j, k));
                    const bool in = glm::length(p - centre) <= 7.5;
                    want += in ? 1 : 0;
                    wantDisc += in && k == 13 ? 1 : 0;
                    QCOMPARE(sphere.at(i, j, k), in);
                    QCOMPARE(disc.at(i, j, k), in && k == 13);
                }
            }
        }
        QCOMPARE(sphere.count(), want);
        QCOMPARE(painted, want);
        QCOMPARE(disc.count(), wantDisc);
        QVERIFY(want > wantDisc && wantDisc > 800); // pi (7.5 / 0.45)^2: about 870 a slice
        QCOMPARE(paintBrush(sphere, g, centre, 7.5, false), want); // erased again
        QVERIFY(!sphere.any());

        // A triangle on slice 13: its voxels whose centre lies inside, by cross products.
        const glm::dvec3 a = g.toPatient({100.25, 100.25, 13}),
                         b = g.toPatient({160.25, 110.25, 13}),
                         c = g.toPatient({120.25, 170.25, 13});
        SegmentMask filled(g.dims);
        fillOutline(filled, g, {a, b, c}, slab);
        const auto side = [](glm::dvec2 p, glm::dvec2 q, glm::dvec2 r) {
            return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
        };
        std::size_t inside = 0;
        for (int j = 90; j < 180; ++j) {
            for (int i = 90; i < 170; ++i) {
                const glm::dvec2 p(i, j);
                const double s1 = side({100.25, 100.25}, {160.25, 110.25}, p);
                const double s2 = side({160.25, 110.25}, {120.25, 170.25}, p);
                const double s3 = side({120.25, 170.25}, {100.25, 100.25}, p);
                const bool in = (s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0);
                inside += in ? 1 : 0;
                QCOMPARE(filled.at(i, j, 13), in);
            }
        }
        QCOMPARE(filled.count(), inside);
    }
};

QTEST_APPLESS_MAIN(TestSegmentSmoothing)
#include "test_segment_smoothing.moc"
