// The measurement model of core/measure: each kind's values from its points, and the
// undo history of every edit on a series' measurements.
#include <QTest>

#include <cmath>

#include "core/measure/MeasurementDocument.h"

using namespace lucent;

namespace {

Measurement make(MeasurementKind kind, std::vector<glm::dvec3> points) {
    Measurement m;
    m.kind = kind;
    m.points = std::move(points);
    return m;
}

} // namespace

class TestMeasurementDocument : public QObject {
    Q_OBJECT
private slots:
    void valuesOfEachKind() {
        const Measurement d = make(MeasurementKind::Distance, {{0, 0, 0}, {3, 4, 12}});
        QCOMPARE(measurementLengthMm(d), 13.0);
        QCOMPARE(measurementValueText(d), std::string("13.0 mm"));

        const Measurement a = make(MeasurementKind::Angle, {{10, 0, 0}, {0, 0, 0}, {1, 1, 0}});
        QVERIFY(std::abs(measurementAngleDegrees(a) - 45.0) < 1e-12);
        const Measurement straight =
            make(MeasurementKind::Angle, {{-1, 0, 0}, {0, 0, 0}, {1, 1e-9, 0}});
        QVERIFY(std::abs(measurementAngleDegrees(straight) - 180.0) < 1e-6);

        // Two endplates 30 degrees apart, drawn in opposite directions: still 30, not 150.
        const double t = 30.0 * M_PI / 180.0;
        const Measurement cobb = make(
            MeasurementKind::CobbAngle,
            {{0, 0, 0}, {10, 0, 0}, {0, 50, 0}, {-10 * std::cos(t), 50 - 10 * std::sin(t), 0}});
        QVERIFY(std::abs(measurementAngleDegrees(cobb) - 30.0) < 1e-9);

        const Measurement bi =
            make(MeasurementKind::Bidirectional, {{0, 0, 0}, {20, 0, 0}, {10, -4, 0}, {10, 4, 0}});
        QCOMPARE(bidirectionalLongAxisMm(bi), 20.0);
        QCOMPARE(bidirectionalShortAxisMm(bi), 8.0);
        QCOMPARE(measurementValueText(bi), std::string("20.0 x 8.0 mm"));

        SlicePlane plane;
        plane.u = {0, 1, 0};
        plane.v = {0, 0, -1};
        const Measurement e = makeEllipseMeasurement(plane, {{5, 6, 7}, 4.0, 2.0});
        const EllipseRoi back = measurementEllipse(e);
        QVERIFY(glm::distance(back.centre, glm::dvec3(5, 6, 7)) < 1e-12);
        QCOMPARE(back.radiusU, 4.0);
        QCOMPARE(back.radiusV, 2.0);
        QVERIFY(e.complete());
        QVERIFY(!make(MeasurementKind::Angle, {{0, 0, 0}}).complete());
    }

    void everyEditUndoesAndRedoes() {
        MeasurementDocument doc;
        QVERIFY(!doc.canUndo());
        const auto first = doc.add(make(MeasurementKind::Distance, {{0, 0, 0}, {1, 0, 0}}));
        const auto second = doc.add(make(MeasurementKind::Arrow, {{0, 0, 0}, {0, 1, 0}}));
        QVERIFY(first != second);
        QCOMPARE(doc.undoText(), std::string("Add arrow"));

        Measurement moved = *doc.find(first);
        moved.points[1] = {5, 0, 0};
        QVERIFY(doc.change(moved));
        QVERIFY(doc.rename(second, "Lesion 1"));
        QVERIFY(!doc.rename(second, "Lesion 1")); // no change, no step
        QVERIFY(doc.remove(first));
        QCOMPARE(doc.measurements().size(), std::size_t(1));
        doc.clear();
        QVERIFY(doc.measurements().empty());

        const std::uint64_t before = doc.revision();
        QVERIFY(doc.undo()); // clear
        QVERIFY(doc.revision() != before);
        QCOMPARE(doc.find(second)->label, std::string("Lesion 1"));
        QVERIFY(doc.undo()); // remove
        QCOMPARE(measurementLengthMm(*doc.find(first)), 5.0);
        QVERIFY(doc.undo()); // rename
        QCOMPARE(doc.find(second)->label, std::string());
        QVERIFY(doc.undo()); // change
        QCOMPARE(measurementLengthMm(*doc.find(first)), 1.0);
        QCOMPARE(doc.redoText(), std::string("Change distance"));
        QVERIFY(doc.redo());
        QCOMPARE(measurementLengthMm(*doc.find(first)), 5.0);
        QVERIFY(doc.undo());
        QVERIFY(doc.undo());
        QVERIFY(doc.undo());
        QVERIFY(doc.measurements().empty());
        QVERIFY(!doc.undo());
        QVERIFY(doc.redo());
        // A new edit drops what could have been redone.
        doc.add(make(MeasurementKind::Distance, {{0, 0, 0}, {2, 0, 0}}));
        QVERIFY(!doc.canRedo());
    }

    void readOnlyOnesStay() {
        MeasurementDocument doc;
        Measurement foreign = make(MeasurementKind::Distance, {{0, 0, 0}, {1, 0, 0}});
        foreign.id = 7;
        foreign.readOnly = true;
        Measurement again = foreign; // a repeated id gets a fresh one
        again.readOnly = false;
        doc.load({foreign, again});
        QVERIFY(!doc.canUndo());
        QCOMPARE(doc.measurements()[0].id, std::uint64_t(7));
        QVERIFY(doc.measurements()[1].id != 7);
        QVERIFY(!doc.remove(7));
        QVERIFY(!doc.rename(7, "x"));
        doc.clear();
        QCOMPARE(doc.measurements().size(), std::size_t(1));
        QVERIFY(doc.measurements()[0].readOnly);
        QVERIFY(doc.add(make(MeasurementKind::Distance, {{0, 0, 0}, {1, 0, 0}})) > 7);
    }
};

QTEST_APPLESS_MAIN(TestMeasurementDocument)
#include "test_measurement_document.moc"
