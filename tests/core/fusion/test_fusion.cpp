// Fusion on the real 28-slice CT: the overlay is a copy of the CT placed in a new Frame of
// Reference by a known rigid transform, so resampling it through that transform must give
// the CT's own values back at every pixel; a checkerboard of the CT with itself is the CT;
// an overlay pixel's colour is the map applied to the resampled value.
#include <QTest>

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "core/fusion/FusionColourMap.h"
#include "core/fusion/FusionCompositor.h"
#include "core/fusion/OverlayNudge.h"
#include "core/fusion/OverlayResampler.h"
#include "core/io/Catalog.h"
#include "core/mpr/CrosshairSlice.h"
#include "tests/support/MovedVolume.h"
#include "tests/support/RealData.h"

using namespace lucent;
using lucent::test::movedCopy;
using lucent::test::rigidAbout;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";

SlicePlane planeThrough(const Volume& v, Orientation o, const glm::dvec3& degrees) {
    SlicePlane p = standardPlane(v.geometry(), o, volumeCentre(v.geometry()), 256, 256);
    const glm::dmat3 turn(
        glm::rotate(glm::rotate(glm::dmat4(1.0), glm::radians(degrees.x), glm::dvec3(1, 0, 0)),
                    glm::radians(degrees.y), glm::dvec3(0, 1, 0)));
    p.u = turn * p.u;
    p.v = turn * p.v;
    return p;
}

// Largest |a - b| where both are numbers; counts pixels where exactly one is NaN.
std::pair<double, int> compare(const std::vector<float>& a, const std::vector<float>& b) {
    double worst = 0.0;
    int mismatched = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (std::isnan(a[i]) != std::isnan(b[i])) {
            ++mismatched;
        } else if (!std::isnan(a[i])) {
            worst = std::max(worst, double(std::abs(a[i] - b[i])));
        }
    }
    return {worst, mismatched};
}

} // namespace

class TestFusion : public QObject {
    Q_OBJECT

    Volume ct_;
    glm::dmat4 move_{1.0};
    Volume moved_;

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        ct_ = loadPath(test::kRealData / kCt);
        QCOMPARE(ct_.dims(), glm::ivec3(512, 512, 28));
        move_ = rigidAbout(volumeCentre(ct_.geometry()), {4.0, -7.0, 10.0}, {12.5, -30.0, 8.0});
        moved_ = movedCopy(ct_, move_);
    }

    void colourMapsHaveTheirEnds() {
        using M = FusionColourMap;
        QCOMPARE(colourLut(M::Grey)[0], (std::array<std::uint8_t, 3>{0, 0, 0}));
        QCOMPARE(colourLut(M::Grey)[200], (std::array<std::uint8_t, 3>{200, 200, 200}));
        QCOMPARE(colourLut(M::HotIron)[0], (std::array<std::uint8_t, 3>{0, 0, 0}));
        QCOMPARE(colourLut(M::HotIron)[127], (std::array<std::uint8_t, 3>{254, 0, 0}));
        QCOMPARE(colourLut(M::HotIron)[255], (std::array<std::uint8_t, 3>{255, 255, 255}));
        QCOMPARE(colourLut(M::Pet)[0], (std::array<std::uint8_t, 3>{0, 0, 0}));
        QCOMPARE(colourLut(M::Pet)[255], (std::array<std::uint8_t, 3>{255, 255, 255}));
        QCOMPARE(colourLut(M::Rainbow)[0], (std::array<std::uint8_t, 3>{0, 0, 255}));
        QCOMPARE(colourLut(M::Rainbow)[255], (std::array<std::uint8_t, 3>{255, 0, 0}));
        // Hot iron grows brighter all the way: no channel ever drops.
        for (int i = 1; i < 256; ++i) {
            for (int c = 0; c < 3; ++c) {
                QVERIFY(colourLut(M::HotIron)[i][c] >= colourLut(M::HotIron)[i - 1][c]);
            }
        }
        for (const M m : kFusionColourMaps) {
            QCOMPARE(colourMapFromName(colourMapName(m)), std::optional<M>(m));
        }
        QCOMPARE(colourMapFromName("Hot_Iron"), std::optional<M>(M::HotIron));
        QVERIFY(!colourMapFromName("jet").has_value());
        // The window picks the entry: the low end is entry 0, the high end entry 255.
        QCOMPARE(mapColour(M::HotIron, 0.0, 5.0, 10.0), colourLut(M::HotIron)[0]);
        QCOMPARE(mapColour(M::HotIron, 10.0, 5.0, 10.0), colourLut(M::HotIron)[255]);
    }

    void overlayThroughItsTransformIsTheBase_data() {
        QTest::addColumn<int>("orientation");
        QTest::addColumn<double>("tiltX");
        QTest::addColumn<double>("slab");
        QTest::newRow("axial") << int(Orientation::Axial) << 0.0 << 0.0;
        QTest::newRow("coronal") << int(Orientation::Coronal) << 0.0 << 0.0;
        QTest::newRow("oblique") << int(Orientation::Sagittal) << 17.0 << 0.0;
        QTest::newRow("axial MIP slab") << int(Orientation::Axial) << 0.0 << 12.0;
    }
    void overlayThroughItsTransformIsTheBase() {
        QFETCH(int, orientation);
        QFETCH(double, tiltX);
        QFETCH(double, slab);
        SlicePlane plane = planeThrough(ct_, Orientation(orientation), {tiltX, 0.0, 0.0});
        plane.slabThickness = slab;
        const std::vector<float> base = sampleImage(ct_, plane);
        const std::vector<float> overlay = sampleOverlay(moved_, plane, move_);
        const auto [worst, mismatched] = compare(base, overlay);
        qInfo("largest difference %.2e HU, %d pixels inside only one", worst, mismatched);
        QVERIFY(worst < 1e-2);
        // Rounding may put a pixel on the very border of the box inside one and not the other.
        QVERIFY(mismatched <= 2);
        // Without the transform the copy is elsewhere: the check can fail.
        const auto [off, offMismatched] = compare(base, sampleImage(moved_, plane));
        QVERIFY(off > 100.0 || offMismatched > 1000);
    }

    void checkerboardOfTheSeriesWithItselfIsTheSeries() {
        const SlicePlane plane = planeThrough(ct_, Orientation::Axial, {0.0, 0.0, 0.0});
        const std::vector<float> values = sampleImage(ct_, plane);
        const std::vector<Rgb32> base = greyToRgb32(windowedGrey(values, 40.0, 400.0));
        FusionStyle style;
        style.colourMap = FusionColourMap::Grey;
        style.center = 40.0;
        style.width = 400.0;
        style.mode = FusionMode::Checkerboard;
        style.checkerPixels = 16;
        const std::vector<Rgb32> fused = composeFusion(
            base, sampleOverlay(ct_, plane, glm::dmat4(1.0)), plane.width, plane.height, style);
        QVERIFY(fused == base);
        // The same through the moved copy and its transform (float rounding may move a
        // value across a grey step: at most one level).
        const std::vector<Rgb32> viaCopy = composeFusion(base, sampleOverlay(moved_, plane, move_),
                                                         plane.width, plane.height, style);
        int differ = 0;
        for (std::size_t i = 0; i < base.size(); ++i) {
            const int d = std::abs(int(base[i] & 0xff) - int(viaCopy[i] & 0xff));
            QVERIFY(d <= 1);
            differ += d;
        }
        QVERIFY(differ < 50);
        // Another window on the overlay shows on its squares, and only there.
        style.center = 500.0;
        const std::vector<Rgb32> other = composeFusion(
            base, sampleOverlay(ct_, plane, glm::dmat4(1.0)), plane.width, plane.height, style);
        int changed = 0;
        for (int y = 0; y < plane.height; ++y) {
            for (int x = 0; x < plane.width; ++x) {
                const std::size_t i = std::size_t(y) * plane.width + x;
                if (!showsOverlay(style, x, y, plane.width)) {
                    QCOMPARE(other[i], base[i]);
                } else {
                    changed += other[i] != base[i];
                }
            }
        }
        QVERIFY(changed > 1000);
    }

    void overlayColourIsTheMapOfTheResampledValue() {
        const SlicePlane plane = planeThrough(ct_, Orientation::Coronal, {8.0, 0.0, 0.0});
        const std::vector<float> values = sampleImage(ct_, plane);
        const std::vector<Rgb32> base = greyToRgb32(windowedGrey(values, 40.0, 400.0));
        const std::vector<float> overlay = sampleOverlay(moved_, plane, move_);
        FusionStyle style;
        style.colourMap = FusionColourMap::HotIron;
        style.center = 300.0;
        style.width = 1200.0;
        style.opacity = 0.4;
        const std::vector<Rgb32> fused =
            composeFusion(base, overlay, plane.width, plane.height, style);
        int checked = 0;
        const glm::dmat4 toIndex = moved_.geometry().patientToIndex() * move_;
        for (int y = 3; y < plane.height; y += 23) {
            for (int x = 5; x < plane.width; x += 19) {
                const std::size_t i = std::size_t(y) * plane.width + x;
                // The overlay value by hand: the pixel's point mapped, then trilinear.
                const glm::dvec3 ijk(toIndex * glm::dvec4(plane.pointAt(x, y), 1.0));
                const double value = sampleAt(moved_, ijk);
                if (std::isnan(value)) {
                    QCOMPARE(fused[i], base[i]);
                    continue;
                }
                QVERIFY(std::abs(value - overlay[i]) < 1e-2);
                const auto c = mapColour(style.colourMap, overlay[i], style.center, style.width);
                const int grey = int(base[i] & 0xff);
                for (int ch = 0; ch < 3; ++ch) {
                    const int expected = int(std::lround(grey + (c[ch] - grey) * 0.4));
                    QCOMPARE(int((fused[i] >> (16 - 8 * ch)) & 0xff), expected);
                }
                ++checked;
            }
        }
        QVERIFY(checked > 50);
        // Below the window's low end the base stays when asked to.
        style.clearBelowWindow = true;
        const std::vector<Rgb32> cleared =
            composeFusion(base, overlay, plane.width, plane.height, style);
        for (std::size_t i = 0; i < overlay.size(); ++i) {
            if (!std::isnan(overlay[i]) && overlay[i] < 300.0 - 600.0) {
                QCOMPARE(cleared[i], base[i]);
            }
        }
    }

    void swipeShowsTheOverlayRightOfTheLine() {
        const SlicePlane plane = planeThrough(ct_, Orientation::Axial, {0.0, 0.0, 0.0});
        const std::vector<float> values = sampleImage(ct_, plane);
        const std::vector<Rgb32> base = greyToRgb32(windowedGrey(values, 40.0, 400.0));
        FusionStyle style;
        style.colourMap = FusionColourMap::Rainbow;
        style.center = 40.0;
        style.width = 400.0;
        style.mode = FusionMode::Swipe;
        style.swipe = 0.25;
        const std::vector<Rgb32> fused =
            composeFusion(base, values, plane.width, plane.height, style);
        for (int y = 0; y < plane.height; y += 7) {
            for (int x = 0; x < plane.width; ++x) {
                const std::size_t i = std::size_t(y) * plane.width + x;
                if (x < 64) {
                    QCOMPARE(fused[i], base[i]);
                } else if (!std::isnan(values[i])) {
                    const auto c = mapColour(style.colourMap, values[i], 40.0, 400.0);
                    QCOMPARE(fused[i], rgb32(c[0], c[1], c[2]));
                }
            }
        }
    }

    void overlayRoiStatisticsAreTheBasesAtTheSameAnatomy() {
        const SlicePlane plane = planeThrough(ct_, Orientation::Axial, {0.0, 0.0, 0.0});
        const EllipseRoi roi{volumeCentre(ct_.geometry()) + glm::dvec3(20.0, -10.0, 0.0), 25.0,
                             15.0};
        const RoiStatistics base = ellipseStatistics(ct_, plane, roi);
        const RoiStatistics overlay = overlayEllipseStatistics(moved_, plane, roi, move_);
        QVERIFY(base.samples > 100);
        QCOMPARE(overlay.samples, base.samples);
        QVERIFY(std::abs(overlay.mean - base.mean) < 1e-3);
        QVERIFY(std::abs(overlay.maximum - base.maximum) < 1e-2);
        QVERIFY(std::abs(overlay.standardDeviation - base.standardDeviation) < 1e-3);
        // Without the transform it measures other anatomy.
        const RoiStatistics elsewhere = ellipseStatistics(moved_, plane, roi);
        QVERIFY(elsewhere.samples == 0 || std::abs(elsewhere.mean - base.mean) > 1.0);
    }

    void nudgeMovesTheOverlaysContent() {
        SlicePlane plane = planeThrough(ct_, Orientation::Axial, {0.0, 0.0, 0.0});
        const std::vector<float> before = sampleOverlay(moved_, plane, move_);
        // Seven pixels to the right: what was at pixel x is now at x + 7.
        const glm::dmat4 shifted = nudgedTransform(move_, plane.u * (7.0 * plane.pixelSize));
        const std::vector<float> after = sampleOverlay(moved_, plane, shifted);
        int compared = 0;
        for (int y = 0; y < plane.height; y += 3) {
            for (int x = 0; x + 7 < plane.width; ++x) {
                const float a = before[std::size_t(y) * plane.width + x];
                const float b = after[std::size_t(y) * plane.width + x + 7];
                if (!std::isnan(a) && !std::isnan(b)) {
                    QVERIFY(std::abs(a - b) < 1e-2);
                    ++compared;
                }
            }
        }
        QVERIFY(compared > 5000);
        // A turn about a point: what was drawn at p is drawn at the turned p.
        const glm::dvec3 pivot = volumeCentre(ct_.geometry());
        const double angle = glm::radians(5.0);
        const glm::dmat4 turned =
            nudgedTransform(move_, glm::dvec3(0.0), angle, plane.normal(), pivot);
        const glm::dmat4 turn = glm::translate(glm::dmat4(1.0), pivot) *
                                glm::rotate(glm::dmat4(1.0), angle, plane.normal()) *
                                glm::translate(glm::dmat4(1.0), -pivot);
        for (const glm::dvec3 p : {pivot + glm::dvec3(30, 10, 0), pivot + glm::dvec3(-40, 25, 0)}) {
            const glm::dvec3 a(move_ * glm::dvec4(p, 1.0));
            const glm::dvec3 b(turned * glm::dvec4(glm::dvec3(turn * glm::dvec4(p, 1.0)), 1.0));
            QVERIFY(glm::length(a - b) < 1e-9);
        }
    }

    void resampledOverlayOnTheBaseGridIsTheBase() {
        const Volume onGrid = resampleOverlay(moved_, ct_.geometry(), move_);
        QCOMPARE(onGrid.dims(), ct_.dims());
        QCOMPARE(onGrid.type(), VoxelType::Float32);
        QCOMPARE(onGrid.frameOfReferenceUid, moved_.frameOfReferenceUid);
        const auto voxels = onGrid.voxels<float>();
        double worst = 0.0;
        for (int k = 0; k < 28; k += 3) {
            for (int j = 0; j < 512; j += 5) {
                for (int i = 0; i < 512; i += 5) {
                    const float v = voxels[ct_.linearIndex(i, j, k)];
                    QVERIFY(!std::isnan(v));
                    worst = std::max(worst, std::abs(v - ct_.value(i, j, k)));
                }
            }
        }
        qInfo("largest difference on the grid %.2e HU", worst);
        QVERIFY(worst < 1e-2);
    }
};

QTEST_GUILESS_MAIN(TestFusion)
#include "test_fusion.moc"
