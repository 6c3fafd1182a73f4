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
