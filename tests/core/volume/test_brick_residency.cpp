// What the GPU's bricks hold, tested without GL: the LOD levels, the voxels of
// a brick box (clamped or mirrored beyond the volume) and their gradients.
#include <QTest>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/volume/BrickResidency.h"
#include "core/volume/LodPyramid.h"
#include "tests/core/raycast/RaycastScenes.h"

using namespace lucent;
using namespace lucent::test;

namespace {

std::size_t volumeOf(glm::ivec3 s) {
    return std::size_t(s.x) * std::size_t(s.y) * std::size_t(s.z);
}

// Index of (i, j, k) in a box of `dims`, x fastest.
std::size_t at(glm::ivec3 dims, int i, int j, int k) {
    return std::size_t(i) +
           std::size_t(dims.x) * (std::size_t(j) + std::size_t(dims.y) * std::size_t(k));
}

template <class T>
std::vector<T> filled(glm::ivec3 dims, const std::function<double(int, int, int)>& f) {
    std::vector<T> out(volumeOf(dims));
    for (int k = 0; k < dims.z; ++k) {
        for (int j = 0; j < dims.y; ++j) {
            for (int i = 0; i < dims.x; ++i) {
                out[at(dims, i, j, k)] = static_cast<T>(f(i, j, k));
            }
        }
    }
    return out;
}

int clampRef(int i, int n) {
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

// Reflects about the edge voxels until inside: -1 -> 1, n -> n - 2.
int mirrorRef(int i, int n) {
    if (n == 1) {
        return 0;
    }
    while (i < 0 || i >= n) {
        i = i < 0 ? -i : 2 * (n - 1) - i;
    }
    return i;
}

} // namespace

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

    // Inside the volume a box is a plain copy of its voxels, x fastest.
    void boxInsideTheVolumeIsACopy() {
        const glm::ivec3 dims(10, 9, 8);
        const std::vector<std::uint16_t> data =
            filled<std::uint16_t>(dims, [](int i, int j, int k) { return i + 10 * j + 100 * k; });
        const glm::ivec3 lo(2, 3, 1), size(5, 4, 3);
        std::vector<std::uint16_t> out(volumeOf(size), 0xFFFF);
        extractBox<std::uint16_t>(data.data(), dims, lo, size, BrickEdge::Clamp, out.data());
        QCOMPARE(out[0], std::uint16_t(2 + 30 + 100));
        QCOMPARE(out[1], std::uint16_t(3 + 30 + 100));     // x fastest
        QCOMPARE(out[5], std::uint16_t(2 + 40 + 100));     // then y
        QCOMPARE(out[20], std::uint16_t(2 + 30 + 200));    // then z
        QCOMPARE(out.back(), std::uint16_t(6 + 60 + 300)); // (4, 3, 2) of the box
        for (int c = 0; c < size.z; ++c) {
            for (int b = 0; b < size.y; ++b) {
                for (int a = 0; a < size.x; ++a) {
                    QCOMPARE(out[at(size, a, b, c)], data[at(dims, lo.x + a, lo.y + b, lo.z + c)]);
                }
            }
        }
        // The whole volume as a box.
        std::vector<std::uint16_t> whole(data.size(), 0);
        extractBox<std::uint16_t>(data.data(), dims, glm::ivec3(0), dims, BrickEdge::Mirror,
                                  whole.data());
        QVERIFY(whole == data);
    }

    // A box reaching out below x, above y and below z repeats the edge voxels.
    void clampRepeatsTheEdgeVoxel() {
        const glm::ivec3 dims(10, 9, 8);
        const std::vector<float> data =
            filled<float>(dims, [&](int i, int j, int k) { return float(at(dims, i, j, k)); });
        const auto v = [&](int i, int j, int k) { return data[at(dims, i, j, k)]; };
        const glm::ivec3 lo(-2, 6, -3), size(4, 5, 5);
        std::vector<float> out(volumeOf(size), -1.0f);
        extractBox<float>(data.data(), dims, lo, size, BrickEdge::Clamp, out.data());
        const auto got = [&](int a, int b, int c) { return out[at(size, a, b, c)]; };
        QCOMPARE(got(0, 0, 0), v(0, 6, 0)); // (-2, 6, -3)
        QCOMPARE(got(2, 0, 3), v(0, 6, 0)); // (0, 6, 0): inside
        QCOMPARE(got(3, 2, 4), v(1, 8, 1)); // (1, 8, 1): inside
        QCOMPARE(got(1, 3, 2), v(0, 8, 0)); // (-1, 9, -1)
        QCOMPARE(got(3, 4, 0), v(1, 8, 0)); // (1, 10, -3)
        for (int c = 0; c < size.z; ++c) {
            for (int b = 0; b < size.y; ++b) {
                for (int a = 0; a < size.x; ++a) {
                    const float want = v(clampRef(lo.x + a, dims.x), clampRef(lo.y + b, dims.y),
                                         clampRef(lo.z + c, dims.z));
                    QCOMPARE(got(a, b, c), want);
                }
            }
        }
        // A box wholly outside, beyond the far corner: all the corner voxel.
        const glm::ivec3 size2(2, 3, 2);
        std::vector<float> far(volumeOf(size2), -1.0f);
        extractBox<float>(data.data(), dims, {12, 9, 8}, size2, BrickEdge::Clamp, far.data());
        for (const float x : far) {
            QCOMPARE(x, v(9, 8, 7));
        }
    }

    // Mirror reflects about the edge voxel (not repeating it): -1 -> 1, n -> n - 2.
    void mirrorReflectsAboutTheEdgeVoxel() {
        const glm::ivec3 dims(10, 9, 8);
        const std::vector<float> data =
            filled<float>(dims, [&](int i, int j, int k) { return float(at(dims, i, j, k)); });
        const auto v = [&](int i, int j, int k) { return data[at(dims, i, j, k)]; };
        const glm::ivec3 lo(-2, 6, -3), size(4, 5, 5);
        std::vector<float> out(volumeOf(size), -1.0f);
        extractBox<float>(data.data(), dims, lo, size, BrickEdge::Mirror, out.data());
        const auto got = [&](int a, int b, int c) { return out[at(size, a, b, c)]; };
        QCOMPARE(got(0, 0, 0), v(2, 6, 3)); // (-2, 6, -3)
        QCOMPARE(got(1, 3, 1), v(1, 7, 2)); // (-1, 9, -2)
        QCOMPARE(got(2, 4, 3), v(0, 6, 0)); // (0, 10, 0)
        QCOMPARE(got(3, 2, 4), v(1, 8, 1)); // inside
        for (int c = 0; c < size.z; ++c) {
            for (int b = 0; b < size.y; ++b) {
                for (int a = 0; a < size.x; ++a) {
                    const float want = v(mirrorRef(lo.x + a, dims.x), mirrorRef(lo.y + b, dims.y),
                                         mirrorRef(lo.z + c, dims.z));
                    QCOMPARE(got(a, b, c), want);
                }
            }
        }
    }

    // Mirroring repeats with period 2 (n - 1) far beyond the edge; a
    // dimension of one voxel gives that voxel everywhere.
    void mirrorFarOutsideAndThinDimensions() {
        const glm::ivec3 dims(3, 1, 2);
        const std::vector<std::int16_t> data =
            filled<std::int16_t>(dims, [](int i, int, int k) { return -(i + 1) - 10 * k; });
        const glm::ivec3 lo(-5, -2, -1), size(12, 3, 3);
        std::vector<std::int16_t> out(volumeOf(size), 0);
        extractBox<std::int16_t>(data.data(), dims, lo, size, BrickEdge::Mirror, out.data());
        // i = -5 .. 6 mirror to 1 0 1 2 1 0 1 2 1 0 1 2; k = -1 .. 1 to 1 0 1.
        const int is[12] = {1, 0, 1, 2, 1, 0, 1, 2, 1, 0, 1, 2};
        const int ks[3] = {1, 0, 1};
        for (int c = 0; c < size.z; ++c) {
            for (int b = 0; b < size.y; ++b) {
                for (int a = 0; a < size.x; ++a) {
                    QCOMPARE(out[at(size, a, b, c)], std::int16_t(-(is[a] + 1) - 10 * ks[c]));
                }
            }
        }
        extractBox<std::int16_t>(data.data(), dims, lo, size, BrickEdge::Clamp, out.data());
        QCOMPARE(out[at(size, 0, 0, 0)], std::int16_t(-1));
        QCOMPARE(out[at(size, 11, 2, 2)], std::int16_t(-3 - 10));
    }

    // component = round(0.5 (v[i+1] - v[i-1]) / unit), x y z then 0; at the
    // volume's edge the missing neighbour is the edge voxel itself.
    void gradientHoldsHalfCentralDifferences() {
        const glm::ivec3 dims(10, 9, 8);
        const auto f = [](int i, int j, int k) { return 3 * i * i - 5 * j + 7 * k; };
        const std::vector<std::int16_t> data = filled<std::int16_t>(dims, f);
        // i 4 .. 6, j 4 .. 8 (the last), k -1 (outside) .. 4.
        const glm::ivec3 lo(4, 4, -1), size(3, 5, 6);
        std::vector<std::int16_t> out(volumeOf(size) * 4, std::int16_t(0x5555));
        const auto got = [&](int a, int b, int c, int ch) {
            return out[4 * at(size, a, b, c) + std::size_t(ch)];
        };
        extractGradientBox<std::int16_t>(data.data(), dims, lo, size, 0.5, out.data());
        // Voxel (5, 5, 4), box (1, 1, 5): halves 0.5 (108 - 48) = 30, -5, 7; / 0.5.
        QCOMPARE(got(1, 1, 5, 0), std::int16_t(60));
        QCOMPARE(got(1, 1, 5, 1), std::int16_t(-10));
        QCOMPARE(got(1, 1, 5, 2), std::int16_t(14));
        QCOMPARE(got(1, 1, 5, 3), std::int16_t(0));
        // k = 0 (c = 1): the neighbour below is k = 0 itself: 0.5 * 7 / 0.5.
        QCOMPARE(got(1, 1, 1, 2), std::int16_t(7));
        QCOMPARE(got(1, 1, 1, 0), std::int16_t(60));
        // j = 8 (b = 4), the last: 0.5 * (-5) / 0.5.
        QCOMPARE(got(0, 4, 3, 1), std::int16_t(-5));
        QCOMPARE(got(0, 4, 3, 0), std::int16_t(3 * (25 - 9))); // i = 4: 0.5 (75 - 27) / 0.5
        // k = -1 (c = 0), outside: the gradient of the edge voxel k = 0.
        for (int ch = 0; ch < 4; ++ch) {
            QCOMPARE(got(2, 2, 0, ch), got(2, 2, 1, ch));
        }
        for (std::size_t n = 3; n < out.size(); n += 4) {
            QCOMPARE(out[n], std::int16_t(0));
        }
        // Rounded to the nearest, not truncated: unit 3 gives 10, -5/3 -> -2, 7/3 -> 2.
        extractGradientBox<std::int16_t>(data.data(), dims, lo, size, 3.0, out.data());
        QCOMPARE(got(1, 1, 5, 0), std::int16_t(10));
        QCOMPARE(got(1, 1, 5, 1), std::int16_t(-2));
        QCOMPARE(got(1, 1, 5, 2), std::int16_t(2));
        QCOMPARE(got(1, 1, 1, 2), std::int16_t(1));  // 3.5 / 3
        QCOMPARE(got(0, 4, 3, 1), std::int16_t(-1)); // -2.5 / 3
    }

    // Unsigned voxels give negative differences; every voxel of a box that
    // reaches outside on all axes agrees with a brute-force difference.
    void gradientOfUnsignedVoxelsEverywhere() {
        const glm::ivec3 dims(7, 6, 5);
        const auto f = [](int i, int j, int k) { return 1000 - 20 * i + j * j - 3 * k * k * k; };
        const std::vector<std::uint16_t> data = filled<std::uint16_t>(dims, f);
        const glm::ivec3 lo(-2, -1, 2), size(11, 8, 5);
        std::vector<std::int16_t> out(volumeOf(size) * 4, std::int16_t(0x5555));
        const double unit = 0.25;
        extractGradientBox<std::uint16_t>(data.data(), dims, lo, size, unit, out.data());
        const auto value = [&](int i, int j, int k) {
            return double(
                data[at(dims, clampRef(i, dims.x), clampRef(j, dims.y), clampRef(k, dims.z))]);
        };
        for (int c = 0; c < size.z; ++c) {
            for (int b = 0; b < size.y; ++b) {
                for (int a = 0; a < size.x; ++a) {
                    const int i = clampRef(lo.x + a, dims.x), j = clampRef(lo.y + b, dims.y),
                              k = clampRef(lo.z + c, dims.z);
                    const double want[3] = {0.5 * (value(i + 1, j, k) - value(i - 1, j, k)) / unit,
                                            0.5 * (value(i, j + 1, k) - value(i, j - 1, k)) / unit,
                                            0.5 * (value(i, j, k + 1) - value(i, j, k - 1)) / unit};
                    const std::int16_t* g = &out[4 * at(size, a, b, c)];
                    for (int ch = 0; ch < 3; ++ch) {
                        QCOMPARE(g[ch], std::int16_t(std::lround(want[ch])));
                    }
                    QCOMPARE(g[3], std::int16_t(0));
                }
            }
        }
        // An interior voxel by hand: (3, 2, 3) at box (5, 3, 1): -20 / 0.25, 4 / 0.25, ...
        const std::int16_t* g = &out[4 * at(size, 5, 3, 1)];
        QCOMPARE(g[0], std::int16_t(-80));
        QCOMPARE(g[1], std::int16_t(16));
        QCOMPARE(g[2], std::int16_t(-3 * (64 - 8) * 2)); // 0.5 * -3 (4^3 - 2^3) / 0.25
    }

    // unit = (max - min) / 2 / 32767 takes the steepest step to +-32767.
    void gradientUnitKeepsTheSteepestStepInRange() {
        const glm::ivec3 dims(10, 3, 3);
        const std::vector<float> data =
            filled<float>(dims, [](int i, int, int) { return i < 5 ? 0.0 : 1000.0; });
        const double unit = 1000.0 / 2.0 / 32767.0;
        std::vector<std::int16_t> out(volumeOf(dims) * 4, 0);
        extractGradientBox<float>(data.data(), dims, glm::ivec3(0), dims, unit, out.data());
        QCOMPARE(out[4 * at(dims, 4, 1, 1)], std::int16_t(32767));
        QCOMPARE(out[4 * at(dims, 5, 1, 1)], std::int16_t(32767));
        QCOMPARE(out[4 * at(dims, 3, 1, 1)], std::int16_t(0));
        QCOMPARE(out[4 * at(dims, 6, 1, 1)], std::int16_t(0));
        QCOMPARE(out[4 * at(dims, 5, 1, 1) + 1], std::int16_t(0));
        const std::vector<float> down =
            filled<float>(dims, [](int i, int, int) { return i < 5 ? 1000.0 : 0.0; });
        extractGradientBox<float>(down.data(), dims, glm::ivec3(0), dims, unit, out.data());
        QCOMPARE(out[4 * at(dims, 4, 1, 1)], std::int16_t(-32767));
    }
};

QTEST_GUILESS_MAIN(TestBrickResidency)
#include "test_brick_residency.moc"
