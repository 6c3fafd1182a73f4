// The measuring tools of the MPR view driven by the mouse (QTest press, move, release)
// on the demo head CT: every kind drawn on the axial plane and on an oblique one, each
// value against the pixels clicked (mm from the plane's pixel size), point handles
// dragged, Esc, and what each view shows. The three views share one SeriesMeasurements.
#include <QApplication>
#include <QLineEdit>
#include <QTest>
#include <QWheelEvent>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include "core/formats/InVesaliusProject.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/mpr/MeasurementNavigation.h"
#include "ui/mpr/MeasurementPainter.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SeriesMeasurements.h"
#include "ui/mpr/SliceView.h"

using namespace lucent;

namespace {

const std::filesystem::path kDemoCt = "/usr/share/doc/invesalius-examples/examples/Cranium.inv3";
constexpr int kSize = 300;

bool near(double a, double b, double tolerance) {
    return std::abs(a - b) <= tolerance;
}

QString describe(double got, double want) {
    return QStringLiteral("got %1, want %2").arg(got, 0, 'g', 10).arg(want, 0, 'g', 10);
}

void drag(QWidget* w, QPoint from, QPoint to) {
    QTest::mousePress(w, Qt::LeftButton, Qt::NoModifier, from);
    QTest::mouseMove(w, (from + to) / 2);
    QTest::mouseMove(w, to);
    QTest::mouseRelease(w, Qt::LeftButton, Qt::NoModifier, to);
}

void click(QWidget* w, QPoint at) {
    QTest::mouseMove(w, at);
    QTest::mouseClick(w, Qt::LeftButton, Qt::NoModifier, at);
}

QPoint pixelOf(const SlicePlane& plane, const glm::dvec3& p) {
    const glm::dvec2 px = plane.pixelOf(p);
    return {static_cast<int>(std::lround(px.x)), static_cast<int>(std::lround(px.y))};
}

// The mean of the volume over the pixels of `plane` inside the ellipse, sampled
// independently of ellipseStatistics: one sample per view pixel.
double meanInside(const Volume& volume, const SlicePlane& plane, const EllipseRoi& e) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < plane.height; ++y) {
        for (int x = 0; x < plane.width; ++x) {
            const glm::dvec3 p = plane.pointAt(x, y);
            const double du = glm::dot(p - e.centre, plane.u) / e.radiusU;
            const double dv = glm::dot(p - e.centre, plane.v) / e.radiusV;
            if (du * du + dv * dv <= 1.0) {
                sum += sampleAt(volume, volume.geometry().toIndex(p));
                ++n;
            }
        }
    }
    return n > 0 ? sum / n : std::nan("");
}

} // namespace

class TestMeasurementTools : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void init();
    void cleanup();
    void everyKindOnTheAxialPlane();
    void everyKindOnAnObliquePlane();
    void handlesAreDraggedAndEachDragIsOneEdit();
    void escapeDropsTheDrawingAndTheArrow();
    void readOnlyMeasurementsCannotBeGrabbed();

private:
    SliceView* view(Orientation o) { return views_[static_cast<int>(o)].get(); }
    const std::vector<Measurement>& measured() const { return measurements_->measurements(); }
    // Draws one of each kind on `v` with the mouse and checks its value against the
    // pixels clicked; returns the ids.
    void drawEveryKind(SliceView* v);
    void checkInPlane(SliceView* v, const Measurement& m);

    std::shared_ptr<const Volume> ct_;
    std::unique_ptr<MprCursor> cursor_;
    std::unique_ptr<SeriesMeasurements> measurements_;
    std::unique_ptr<SliceView> views_[3];
};

void TestMeasurementTools::initTestCase() {
    if (!std::filesystem::exists(kDemoCt)) {
        QSKIP("the demo CT (Debian package invesalius-examples) is not installed");
    }
    ct_ = std::make_shared<Volume>(readInVesalius(kDemoCt));
    QCOMPARE(QString::fromStdString(ct_->modality), QStringLiteral("CT"));
}

void TestMeasurementTools::init() {
    cursor_ = std::make_unique<MprCursor>();
    cursor_->setPoint(ct_->geometry().toPatient(glm::dvec3(ct_->dims() / 2)));
    cursor_->setWindow(40.0, 400.0);
    measurements_ = std::make_unique<SeriesMeasurements>(ct_);
    for (const Orientation o : {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
        auto& v = views_[static_cast<int>(o)];
        v = std::make_unique<SliceView>(o, cursor_.get());
        v->resize(kSize, kSize);
        v->setVolume(ct_);
        v->setMeasurements(measurements_.get());
        v->show();
        QVERIFY(QTest::qWaitForWindowExposed(v.get()));
    }
}

void TestMeasurementTools::cleanup() {
    for (auto& v : views_) {
        v.reset();
    }
    measurements_.reset();
    cursor_.reset();
}

void TestMeasurementTools::checkInPlane(SliceView* v, const Measurement& m) {
    const SlicePlane plane = v->plane();
    QVERIFY2(distanceFromPlane(m, plane) < 1e-6,
             qPrintable(describe(distanceFromPlane(m, plane), 0)));
    QVERIFY(glm::distance(glm::normalize(m.plane.normal()), glm::normalize(plane.normal())) < 1e-9);
    QVERIFY(measurementInPlane(m, plane, v->measurementTolerance()));
}

void TestMeasurementTools::drawEveryKind(SliceView* v) {
    const double ps = v->plane().pixelSize;
    const double tolerance = 1e-6;
    const std::size_t before = measured().size();

    // Distance: a drag of 100 pixels across.
    QTest::keyClick(v, Qt::Key_D);
    QCOMPARE(v->tool(), SliceTool::Distance);
    drag(v, {40, 50}, {140, 50});
    QCOMPARE(measured().size(), before + 1);
    QCOMPARE(measured().back().kind, MeasurementKind::Distance);
    QVERIFY2(near(measurementLengthMm(measured().back()), 100.0 * ps, tolerance),
             qPrintable(describe(measurementLengthMm(measured().back()), 100.0 * ps)));
    checkInPlane(v, measured().back());

    // Angle: the first arm dragged to the vertex, the second arm's end clicked: 90 degrees.
    QTest::keyClick(v, Qt::Key_A);
    drag(v, {60, 120}, {120, 120});
    QCOMPARE(measured().size(), before + 1); // not yet: the second arm is missing
    click(v, {120, 70});
    QCOMPARE(measured().size(), before + 2);
    QCOMPARE(measured().back().kind, MeasurementKind::Angle);
    QVERIFY(near(measurementAngleDegrees(measured().back()), 90.0, 1e-9));
    QVERIFY(glm::distance(measured().back().points[1], v->plane().pointAt(120, 120)) < tolerance);
    // ... or three clicks: arms (-60, 0) and (60, -60) from the vertex are 135 degrees apart.
    click(v, {60, 200});
    click(v, {120, 200});
    QCOMPARE(measured().size(), before + 2);
    click(v, {180, 140});
    QCOMPARE(measured().size(), before + 3);
    QVERIFY(near(measurementAngleDegrees(measured().back()), 135.0, 1e-9));
    checkInPlane(v, measured().back());

    // Cobb angle: two lines dragged; the second rises 30 pixels over 100.
    QTest::keyClick(v, Qt::Key_K);
    drag(v, {40, 160}, {140, 160});
    QCOMPARE(measured().size(), before + 3);
    drag(v, {40, 230}, {140, 260});
    QCOMPARE(measured().size(), before + 4);
    QCOMPARE(measured().back().kind, MeasurementKind::CobbAngle);
    const double cobb = std::atan2(30.0, 100.0) * 180.0 / std::numbers::pi;
    QVERIFY2(near(measurementAngleDegrees(measured().back()), cobb, 1e-9),
             qPrintable(describe(measurementAngleDegrees(measured().back()), cobb)));
    checkInPlane(v, measured().back());

    // Arrow: dragged from the finding, then its text typed over the view.
    QTest::keyClick(v, Qt::Key_T);
    drag(v, {200, 100}, {250, 60});
    QCOMPARE(measured().size(), before + 4); // waits for the text
    QLineEdit* editor = v->measurementTools().textEditor();
    QVERIFY(editor != nullptr);
    QVERIFY(editor->isVisible());
    QTest::keyClicks(editor, QStringLiteral("Nodule"));
    QTest::keyClick(editor, Qt::Key_Return);
    QCOMPARE(measured().size(), before + 5);
    const Measurement arrow = measured().back();
    QCOMPARE(arrow.kind, MeasurementKind::Arrow);
    QCOMPARE(arrow.text, std::string("Nodule"));
    QVERIFY(glm::distance(arrow.points[1], v->plane().pointAt(200, 100)) < tolerance); // head
    QVERIFY(glm::distance(arrow.points[0], v->plane().pointAt(250, 60)) < tolerance);  // tail
    QVERIFY(v->measurementTools().textEditor() == nullptr);
    checkInPlane(v, arrow);

    // Bidirectional: the long axis dragged; the short axis half as long, perpendicular.
    QTest::keyClick(v, Qt::Key_B);
    drag(v, {60, 280}, {160, 280});
    QCOMPARE(measured().size(), before + 6);
    const Measurement bi = measured().back();
    QCOMPARE(bi.kind, MeasurementKind::Bidirectional);
    QVERIFY(near(bidirectionalLongAxisMm(bi), 100.0 * ps, tolerance));
    QVERIFY(near(bidirectionalShortAxisMm(bi), 50.0 * ps, tolerance));
    QVERIFY(near(glm::dot(bi.points[1] - bi.points[0], bi.points[3] - bi.points[2]), 0.0, 1e-9));
    checkInPlane(v, bi);

    // Ellipse: its box dragged, 60 x 40 pixels; statistics in HU.
    QTest::keyClick(v, Qt::Key_E);
    drag(v, {170, 170}, {230, 210});
    QCOMPARE(measured().size(), before + 7);
    const Measurement e = measured().back();
    QCOMPARE(e.kind, MeasurementKind::Ellipse);
    const EllipseRoi roi = measurementEllipse(e);
    QVERIFY(near(roi.radiusU, 30.0 * ps, tolerance));
    QVERIFY(near(roi.radiusV, 20.0 * ps, tolerance));
    QVERIFY(near(e.statistics.areaMm2, std::numbers::pi * roi.radiusU * roi.radiusV, 1e-6));
    QCOMPARE(e.unit, std::string("HU"));
    QVERIFY(e.statistics.samples > 100);
    const double mean = meanInside(*ct_, v->plane(), roi);
    QVERIFY2(near(e.statistics.mean, mean, std::max(5.0, 0.1 * e.statistics.standardDeviation)),
             qPrintable(describe(e.statistics.mean, mean)));
    checkInPlane(v, e);
    // The value is drawn beside it.
    QVERIFY(measurementOverlayText(e).contains(QStringLiteral(" HU")));
    QVERIFY(!v->grab().isNull());
    QTest::keyClick(v, Qt::Key_Escape);
    QCOMPARE(v->tool(), SliceTool::Crosshair);
}

void TestMeasurementTools::everyKindOnTheAxialPlane() {
    SliceView* axial = view(Orientation::Axial);
    const glm::dvec3 crosshair = cursor_->point();
    drawEveryKind(axial);
    QCOMPARE(measured().size(), std::size_t(7));
    // Measuring leaves the crosshair alone.
    QCOMPARE(cursor_->point(), crosshair);
    for (const Measurement& m : measured()) {
        QCOMPARE(measurementPlaneName(m), QStringLiteral("Axial"));
        QCOMPARE(measurementSlice(m, ct_->geometry()).value_or(-1), ct_->dims().z / 2 + 1);
        // Not on the coronal view, nor on the next axial slice.
        QVERIFY(!measurementInPlane(m, view(Orientation::Coronal)->plane(),
                                    view(Orientation::Coronal)->measurementTolerance()));
    }
    QTest::keyClick(axial, Qt::Key_D);
    QTest::mouseMove(axial, {150, 150});
    QWheelEvent next(QPointF(150, 150), axial->mapToGlobal(QPointF(150, 150)), QPoint(),
                     QPoint(0, 120), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(axial, &next);
    for (const Measurement& m : measured()) {
        QVERIFY(!measurementInPlane(m, axial->plane(), axial->measurementTolerance()));
    }
}

void TestMeasurementTools::everyKindOnAnObliquePlane() {
    // Shift-drag on the axial view turns the coronal plane 25 degrees about the axial normal.
    SliceView* axial = view(Orientation::Axial);
    const glm::dvec2 c = axial->plane().pixelOf(cursor_->point());
    const QPoint centre(int(std::lround(c.x)), int(std::lround(c.y)));
    const double angle = 25.0 * std::numbers::pi / 180.0;
    const QPoint end = centre + QPoint(int(std::lround(80 * std::cos(angle))),
                                       int(std::lround(80 * std::sin(angle))));
    QTest::mousePress(axial, Qt::LeftButton, Qt::ShiftModifier, centre + QPoint(80, 0));
    QTest::mouseMove(axial, end);
    QTest::mouseRelease(axial, Qt::LeftButton, Qt::ShiftModifier, end);
    SliceView* coronal = view(Orientation::Coronal);
    const glm::dvec3 n = glm::normalize(coronal->plane().normal());
    QVERIFY2(std::abs(n.y) < 0.95 && std::abs(n.z) < 1e-9, "the coronal plane is not oblique");

    drawEveryKind(coronal);
    QCOMPARE(measured().size(), std::size_t(7));
    for (const Measurement& m : measured()) {
        QCOMPARE(measurementPlaneName(m), QStringLiteral("Oblique"));
        QVERIFY(!measurementSlice(m, ct_->geometry()).has_value());
        QVERIFY(!measurementInPlane(m, axial->plane(), axial->measurementTolerance()));
    }
    // Back to standard planes and elsewhere; the list's jump turns the planes back.
    const Measurement distance = measured().front();
    QTest::keyClick(coronal, Qt::Key_O);
    cursor_->setPoint(cursor_->point() + glm::dvec3(10.0, 20.0, 30.0));
    QVERIFY(!measurementInPlane(distance, coronal->plane(), coronal->measurementTolerance()));
    showMeasurement(*cursor_, distance);
    QVERIFY(measurementInPlane(distance, coronal->plane(), coronal->measurementTolerance()));
    QVERIFY(distanceFromPlane(distance, coronal->plane()) < 1e-6);
    // The axial plane, turned about its own normal only, stays upright.
    QCOMPARE(cursor_->rotation(Orientation::Axial), glm::dmat3(1.0));
}

void TestMeasurementTools::handlesAreDraggedAndEachDragIsOneEdit() {
    SliceView* axial = view(Orientation::Axial);
    const double ps = axial->plane().pixelSize;
    QTest::keyClick(axial, Qt::Key_B);
    drag(axial, {60, 100}, {160, 100});
    const std::uint64_t id = measured().back().id;
    // The short axis' lower end, 25 pixels below the middle, dragged 10 further (and
    // sideways, which it does not follow).
    const QPoint lower = pixelOf(axial->plane(), measured().back().points[3]);
    QCOMPARE(lower, QPoint(110, 125));
    const std::uint64_t revision = measurements_->document().revision();
    drag(axial, lower, lower + QPoint(4, 10));
    QCOMPARE(measured().size(), std::size_t(1)); // moved, not drawn anew
    QCOMPARE(measurements_->document().revision(), revision + 1);
    QCOMPARE(measurements_->document().undoText(), std::string("Change bidirectional"));
    const Measurement bi = *measurements_->find(id);
    QVERIFY(std::abs(bidirectionalShortAxisMm(bi) - 60.0 * ps) < 1e-6);
    QVERIFY(std::abs(bidirectionalLongAxisMm(bi) - 100.0 * ps) < 1e-6);
    QVERIFY(std::abs(glm::dot(bi.points[1] - bi.points[0], bi.points[3] - bi.points[2])) < 1e-9);

    // A distance's end, with the crosshair tool: handles are grabbed whatever the tool.
    QTest::keyClick(axial, Qt::Key_D);
    drag(axial, {40, 200}, {140, 200});
    QTest::keyClick(axial, Qt::Key_Escape);
    const glm::dvec3 crosshair = cursor_->point();
    drag(axial, {140, 200}, {140, 260});
    QCOMPARE(cursor_->point(), crosshair);
    const double want = std::hypot(100.0, 60.0) * ps;
    QVERIFY2(std::abs(measurementLengthMm(measured().back()) - want) < 1e-6,
             qPrintable(describe(measurementLengthMm(measured().back()), want)));
    QCOMPARE(measurements_->selected(), measured().back().id);

    // An ellipse's side handle sets that semi-axis; its statistics follow.
    QTest::keyClick(axial, Qt::Key_E);
    drag(axial, {170, 170}, {230, 210});
    const Measurement before = measured().back();
    const QPoint right = pixelOf(axial->plane(), before.points[1]);
    drag(axial, right, right + QPoint(20, 0));
    const Measurement after = measured().back();
    QVERIFY(std::abs(measurementEllipse(after).radiusU - 50.0 * ps) < 1e-6);
    QVERIFY(std::abs(after.statistics.areaMm2 - std::numbers::pi * 50.0 * 20.0 * ps * ps) < 1e-6);
    QVERIFY(after.statistics.areaMm2 > before.statistics.areaMm2 * 1.6);
    QVERIFY(after.statistics.samples > before.statistics.samples);

    // Undo takes each drag back whole.
    QVERIFY(measurements_->undo());
    QCOMPARE(measured().back().points, before.points);
    QVERIFY(measurements_->undo()); // the ellipse's add
    QVERIFY(measurements_->undo()); // the distance's drag
    QVERIFY(std::abs(measurementLengthMm(measured().back()) - 100.0 * ps) < 1e-6);
}

void TestMeasurementTools::escapeDropsTheDrawingAndTheArrow() {
    SliceView* axial = view(Orientation::Axial);
    QTest::keyClick(axial, Qt::Key_A);
    drag(axial, {60, 120}, {120, 120});
    QVERIFY(axial->measurementTools().busy());
    QTest::keyClick(axial, Qt::Key_Escape);
    QVERIFY(!axial->measurementTools().busy());
    QCOMPARE(axial->tool(), SliceTool::Angle); // Esc while drawing keeps the tool
    QVERIFY(measured().empty());

    QTest::keyClick(axial, Qt::Key_T);
    drag(axial, {200, 100}, {250, 60});
    QLineEdit* editor = axial->measurementTools().textEditor();
    QVERIFY(editor != nullptr);
    QTest::keyClicks(editor, QStringLiteral("never"));
    QTest::keyClick(editor, Qt::Key_Escape);
    QVERIFY(measured().empty());
    QVERIFY(axial->measurementTools().textEditor() == nullptr);
    QVERIFY(!measurements_->document().canUndo());
}

void TestMeasurementTools::readOnlyMeasurementsCannotBeGrabbed() {
    SliceView* axial = view(Orientation::Axial);
    Measurement foreign;
    foreign.kind = MeasurementKind::Distance;
    foreign.plane = axial->plane();
    foreign.points = {axial->plane().pointAt(50, 50), axial->plane().pointAt(150, 50)};
    foreign.readOnly = true;
    measurements_->load({foreign});
    const glm::dvec3 crosshair = cursor_->point();
    drag(axial, {150, 50}, {150, 120}); // the crosshair tool: moves the crosshair instead
    QCOMPARE(measured().front().points, foreign.points);
    QVERIFY(cursor_->point() != crosshair);
    QTest::keyClick(axial, Qt::Key_Delete);
    QCOMPARE(measured().size(), std::size_t(1));
}

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestMeasurementTools test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_measurement_tools.moc"
