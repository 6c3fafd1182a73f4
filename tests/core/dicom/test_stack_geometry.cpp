// planStack on positions alone: ordering, spacing, duplicates, tilt, gaps.
#include <QTest>

#include "core/dicom/StackGeometry.h"

using namespace lucent;

namespace {

StackInput axialStack(const std::vector<double>& zs) {
    StackInput in;
    in.columns = 4;
    in.rows = 3;
    in.pixelSpacing = {0.5, 0.75};
    for (double z : zs) {
        in.positions.emplace_back(-10.0, 20.0, z);
    }
    return in;
}

bool near(const glm::dvec3& a, const glm::dvec3& b, double tol = 1e-9) {
    return glm::length(a - b) <= tol;
}

// The oblique MR of the defect report: 20 images of 256x256 at 0.86 mm, about
// 7 mm apart, the plane tilted 8 degrees from axial. Each image drifts
// `drift` mm in plane over the stack (along the columns) and image `moved`
// sits `offset` mm off its place along the normal; the gaps vary by about
// 0.1 mm besides.
StackInput obliqueMr(double drift, int moved = -1, double offset = 0.0) {
    StackInput in;
    in.columns = in.rows = 256;
    in.pixelSpacing = {0.86, 0.86};
    const double a = glm::radians(8.0);
    in.rowDir = {1.0, 0.0, 0.0};
    in.colDir = {0.0, std::cos(a), std::sin(a)};
    const glm::dvec3 normal = glm::cross(in.rowDir, in.colDir);
    double z = 0.0;
    for (int k = 0; k < 20; ++k) {
        const double along = z + (k == moved ? offset : 0.0);
        in.positions.push_back(glm::dvec3(-110.0, -95.0, -40.0) + normal * along +
                               in.colDir * (drift * k / 19.0));
        z += 7.0 + 0.05 * std::sin(1.7 * k); // gaps 6.95 .. 7.05 mm
    }
    return in;
}

} // namespace

class TestStackGeometry : public QObject {
    Q_OBJECT
private slots:
    void sortsAlongNormalNotInputOrder() {
        const StackPlan p = planStack(axialStack({3.0, 1.0, 2.0, 0.0}));
        QCOMPARE(p.order, (std::vector<int>{3, 1, 2, 0}));
        QVERIFY(!p.resample);
        QCOMPARE(p.geometry.dims, glm::ivec3(4, 3, 4));
        QVERIFY(near(p.geometry.spacing, {0.5, 0.75, 1.0}));
        QVERIFY(near(p.geometry.origin, {-10.0, 20.0, 0.0}));
        QVERIFY(p.warnings.empty());
    }
    void normalFollowsRowCrossColumn() {
        // Coronal-like: rows along +x, columns along -z; normal = x cross -z = +y.
        StackInput in = axialStack({});
        in.rowDir = {1, 0, 0};
        in.colDir = {0, 0, -1};
        for (double y : {5.0, -5.0, 0.0}) {
            in.positions.emplace_back(0.0, y, 100.0);
        }
        const StackPlan p = planStack(in);
        QVERIFY(near(p.geometry.direction[2], {0, 1, 0}));
        QCOMPARE(p.order, (std::vector<int>{1, 2, 0}));
        QVERIFY(near(p.geometry.origin, {0.0, -5.0, 100.0}));
        QCOMPARE(p.geometry.spacing.z, 5.0);
    }
    void dropsDuplicatePositionsKeepingTheFirst() {
        const StackPlan p = planStack(axialStack({0.0, 1.0, 1.0, 2.0}));
        QCOMPARE(p.order, (std::vector<int>{0, 1, 3}));
        QCOMPARE(p.dropped, (std::vector<int>{2}));
        QVERIFY(!p.resample);
    }
    void missingSliceIsResampledOnTheRegularGrid() {
        const StackPlan p = planStack(axialStack({0.0, 1.0, 2.0, 4.0, 5.0}));
        QVERIFY(p.resample);
        QVERIFY(p.unevenGaps);
        QCOMPARE(p.missingSlices, 1);
        QCOMPARE(p.geometry.dims.z, 6);
        QCOMPARE(p.geometry.spacing.z, 1.0);
        // The acquired slices land exactly on grid slices 0, 1, 2, 4, 5.
        QCOMPARE(p.placement[3].z, 4.0);
        QCOMPARE(p.warnings.size(), std::size_t(1));
        QVERIFY(QString::fromStdString(p.warnings[0]).contains("1 missing slice"));
    }
    void unevenGapsUseTheSmallestGap() {
        const StackPlan p = planStack(axialStack({0.0, 1.0, 5.0, 12.0}));
        QVERIFY(p.resample);
        QCOMPARE(p.geometry.dims.z, 13);
        QCOMPARE(p.geometry.spacing.z, 1.0);
        QVERIFY(QString::fromStdString(p.warnings[0]).contains("uneven slice gaps"));
    }
    void tiltWidensTheGridAndPlacesEachSlice() {
        // Steps of 1 mm along z and 0.5 mm along y: 26.57 degrees.
        StackInput in = axialStack({});
        for (int k = 0; k < 5; ++k) {
            in.positions.emplace_back(0.0, 0.5 * k, 1.0 * k);
        }
        const StackPlan p = planStack(in);
        QVERIFY(p.resample);
        QVERIFY(std::abs(p.tiltDegrees - 26.565) < 0.01);
        QCOMPARE(p.geometry.dims.z, 5);
        // 3 rows of 0.75 mm plus a 2 mm shift: rows 0 .. (1.5 + 2) / 0.75.
        QCOMPARE(p.geometry.dims.y, 6);
        QCOMPARE(p.geometry.dims.x, 4);
        QVERIFY(near(p.placement[4], {0.0, 2.0 / 0.75, 4.0}, 1e-9));
        QVERIFY(QString::fromStdString(p.warnings[0]).contains("gantry tilt 26.565 deg"));
    }
    void tinyDriftIsNotATilt() {
        StackInput in = axialStack({});
        for (int k = 0; k < 30; ++k) {
            in.positions.emplace_back(1e-4 * k, 0.0, 4.0 * k);
        }
        const StackPlan p = planStack(in);
        QVERIFY(!p.resample);
        QVERIFY(p.warnings.empty());
    }
    void obliqueMrWithinTolerancesKeepsItsGrid() {
        // 0.056 mm over the stack is 0.024 degrees off the normal.
        const StackPlan p = planStack(obliqueMr(0.056));
        QVERIFY(!p.resample);
        QVERIFY(!p.unevenGaps);
        QCOMPARE(p.geometry.dims, glm::ivec3(256, 256, 20));
        QVERIFY(std::abs(p.tiltDegrees - 0.024) < 0.001);
        QVERIFY(std::abs(p.shiftPixels - 0.056 / 0.86) < 1e-6);
        QVERIFY(p.gridDeviation < kGridTolerance);
        QCOMPARE(p.warnings.size(), std::size_t(2));
        QVERIFY(QString::fromStdString(p.warnings[0]).contains("kept the acquired grid"));
        QVERIFY(QString::fromStdString(p.warnings[0]).contains("0.024 deg"));
        QVERIFY(QString::fromStdString(p.warnings[1]).contains("slice gaps vary"));
        QVERIFY(QString::fromStdString(p.warnings[1]).contains("kept the acquired grid"));
    }
    void inPlaneShiftBothSidesOfTheTolerance() {
        const double pixel = 0.86;
        const StackPlan below = planStack(obliqueMr(0.99 * kShiftTolerancePixels * pixel));
        QVERIFY(!below.resample);
        QCOMPARE(below.geometry.dims, glm::ivec3(256, 256, 20));
        const StackPlan above = planStack(obliqueMr(1.01 * kShiftTolerancePixels * pixel));
        QVERIFY(above.resample);
        QVERIFY(!above.unevenGaps);
        QCOMPARE(above.geometry.dims, glm::ivec3(256, 257, 20));
        QVERIFY(QString::fromStdString(above.warnings[0]).contains("gantry tilt"));
    }
    void gridDeviationBothSidesOfTheTolerance() {
        // Image 9 moved along the normal: its deviation is offset / 7 mm,
        // give or take the 0.05 mm the gaps vary by.
        const StackPlan below = planStack(obliqueMr(0.0, 9, 0.04 * 7.0));
        QVERIFY(!below.resample);
        QVERIFY(below.gridDeviation < kGridTolerance);
        QCOMPARE(below.geometry.dims, glm::ivec3(256, 256, 20));
        const StackPlan above = planStack(obliqueMr(0.0, 9, 0.06 * 7.0));
        QVERIFY(above.resample);
        QVERIFY(above.unevenGaps);
        QVERIFY(above.gridDeviation > kGridTolerance);
        QCOMPARE(above.geometry.dims.x, 256);
        QCOMPARE(above.geometry.dims.y, 256); // no in-plane drift: the plane is not widened
        QVERIFY(QString::fromStdString(above.warnings.back()).contains("uneven slice gaps"));
    }
    void smallGapsThatAddUpAreResampled() {
        // Gaps growing steadily from 0.98 to 1.02 mm vary by only 4 %, but
        // over 100 slices the middle ones end up far from an even grid.
        std::vector<double> zs{0.0};
        for (int k = 0; k < 99; ++k) {
            zs.push_back(zs.back() + 0.98 + 0.04 * k / 98.0);
        }
        const StackPlan p = planStack(axialStack(zs));
        QVERIFY(p.gridDeviation > kGridTolerance);
        QVERIFY(p.resample);
    }
    void singleImageUsesSliceThickness() {
        StackInput in = axialStack({7.0});
        in.sliceThickness = 2.5;
        const StackPlan p = planStack(in);
        QCOMPARE(p.geometry.dims.z, 1);
        QCOMPARE(p.geometry.spacing.z, 2.5);
    }
    void imagesInOnePlaneAreNotAStack() {
        StackInput in = axialStack({});
        in.positions = {{0, 0, 0}, {5, 0, 0}};
        QVERIFY(!planStack(in).error.empty());
    }
};

QTEST_APPLESS_MAIN(TestStackGeometry)
#include "test_stack_geometry.moc"
