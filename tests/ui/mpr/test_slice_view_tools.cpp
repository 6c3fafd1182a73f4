// The MPR view's tools with QTest mouse and key events on real SliceViews: window
// presets, zoom and pan, thick slabs, distance and ellipse ROI measurements, oblique
// planes by rotating the crosshair, cine, and the overlay's scale bar and series text.
#include <QApplication>
#include <QMenu>
#include <QTest>
#include <QWheelEvent>

#include <cmath>
#include <memory>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "tests/support/OffscreenPlatform.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SeriesMeasurements.h"
#include "ui/mpr/SliceOverlay.h"
#include "ui/mpr/SliceView.h"

using namespace lucent;

namespace {

double field(const glm::dvec3& p) {
    return p.x + 10 * p.y + 100 * p.z;
}

// value = field(LPS position); a block of i 10..29, j 8..21 holds 35 HU when `uniformBlock`.
std::shared_ptr<const Volume> makeVolume(bool uniformBlock) {
    VolumeGeometry g;
    g.dims = {40, 30, 20};
    g.spacing = {0.7, 0.9, 2.0};
    g.origin = {-14.0, -13.0, 50.0};
    auto volume = std::make_shared<Volume>(g, VoxelType::Float32);
    auto voxels = volume->voxels<float>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const bool block = i >= 10 && i < 30 && j >= 8 && j < 22;
                voxels[volume->linearIndex(i, j, k)] =
                    uniformBlock ? (block ? 35.0f : -1000.0f)
                                 : static_cast<float>(field(g.toPatient(glm::dvec3(i, j, k))));
            }
        }
    }
    volume->modality = "CT";
    volume->patientName = "Doe^Jane";
    volume->patientId = "P-0042";
    volume->studyDate = "20240131";
    volume->description = "Head 1.0 H30s";
    return volume;
}

void wheel(QWidget* w, int delta, const QPointF& pos, Qt::KeyboardModifiers modifiers) {
    QWheelEvent event(pos, w->mapToGlobal(pos), QPoint(), QPoint(0, delta), Qt::NoButton, modifiers,
                      Qt::NoScrollPhase, false);
    QApplication::sendEvent(w, &event);
}

bool near(double a, double b, double tolerance = 1e-9) {
    return std::abs(a - b) <= tolerance;
}

QString text(const glm::dvec3& v) {
    return QStringLiteral("(%1, %2, %3)").arg(v.x).arg(v.y).arg(v.z);
}

} // namespace

class TestSliceViewTools : public QObject {
    Q_OBJECT

private slots:
    void init();
    void cleanup();
    void presetKeysSetWindowInAllViews();
    void presetFromContextMenu();
    void rightClickOpensMenuAndKeepsWindow();
    void ctrlWheelZoomsAboutMouse();
    void middleDragPans();
    void slabKeysThickenThePlane();
    void distanceBetweenTwoClicks();
    void distanceByDrag();
    void ellipseRoiOverUniformRegion();
    void shiftDragMakesObliquePlanes();
    void cineKeyPlaysThroughSlices();
    void overlayHelpers();

private:
    SliceView* view(Orientation o) { return views_[static_cast<int>(o)].get(); }
    void setVolume(std::shared_ptr<const Volume> volume);
    const std::vector<Measurement>& measured() const { return measurements_->measurements(); }

    std::unique_ptr<MprCursor> cursor_;
    std::unique_ptr<SliceView> views_[3];
    // The series' measurements, shared by the three views as in the main window.
    std::unique_ptr<SeriesMeasurements> measurements_;
};

void TestSliceViewTools::init() {
    cursor_ = std::make_unique<MprCursor>();
    cursor_->setWindow(40.0, 400.0);
    for (const Orientation o : {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
        auto& v = views_[static_cast<int>(o)];
        v = std::make_unique<SliceView>(o, cursor_.get());
        v->resize(240, 200);
        v->show();
        QVERIFY(QTest::qWaitForWindowExposed(v.get()));
    }
    setVolume(makeVolume(false));
}

void TestSliceViewTools::setVolume(std::shared_ptr<const Volume> volume) {
    cursor_->setPoint(volume->geometry().toPatient(glm::dvec3(volume->dims() / 2)));
    auto measurements = std::make_unique<SeriesMeasurements>(volume);
    for (auto& v : views_) {
        v->setVolume(volume);
        v->setMeasurements(measurements.get());
    }
    measurements_ = std::move(measurements);
}

void TestSliceViewTools::cleanup() {
    for (auto& v : views_) {
        v.reset();
    }
    measurements_.reset();
    cursor_.reset();
}

void TestSliceViewTools::presetKeysSetWindowInAllViews() {
    SliceView* axial = view(Orientation::Axial);
    QTest::keyClick(axial, Qt::Key_4); // lung
    QCOMPARE(cursor_->windowWidth(), 1500.0);
    QCOMPARE(cursor_->windowCenter(), -600.0);
    // Every linked view maps its values through the new window.
    for (const Orientation o : {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
        SliceView* v = view(o);
        const QImage image = v->image();
        for (const QPoint px : {QPoint(120, 100), QPoint(100, 90), QPoint(140, 110)}) {
            const double value = v->valueAt(px);
            QCOMPARE(qGray(image.pixel(px)), int(windowToGrey(value, -600.0, 1500.0)));
        }
    }
    QTest::keyClick(view(Orientation::Sagittal), Qt::Key_1); // brain
    QCOMPARE(cursor_->windowWidth(), 80.0);
    QCOMPARE(cursor_->windowCenter(), 40.0);
    QTest::keyClick(view(Orientation::Coronal), Qt::Key_8); // bone
    QCOMPARE(cursor_->windowWidth(), 1800.0);
    QCOMPARE(cursor_->windowCenter(), 400.0);
}

void TestSliceViewTools::presetFromContextMenu() {
    QMenu menu;
    view(Orientation::Coronal)->fillContextMenu(menu);
    QMenu* presets = nullptr;
    for (QAction* a : menu.actions()) {
        if (a->menu() && a->text() == QStringLiteral("Window preset")) {
            presets = a->menu();
        }
    }
    QVERIFY(presets);
    // The eight presets, a separator, and the inverted grey switch (off for a CT).
    QCOMPARE(presets->actions().size(), 10);
    QVERIFY(presets->actions()[4]->text().startsWith(QStringLiteral("Mediastinum")));
    presets->actions()[4]->trigger();
    QCOMPARE(cursor_->windowWidth(), 350.0);
    QCOMPARE(cursor_->windowCenter(), 50.0);

    QAction* inverted = presets->actions()[9];
    QCOMPARE(inverted->text(), QStringLiteral("Inverted grey"));
    QVERIFY(inverted->isCheckable() && !inverted->isChecked());
    SliceView* v = view(Orientation::Coronal);
    const QImage normal = v->image().copy();
    inverted->trigger();
    QVERIFY(cursor_->invertedGrey());
    const QImage turned = v->image();
    QCOMPARE(turned.size(), normal.size());
    for (const QPoint p : {QPoint(10, 10), QPoint(normal.width() / 2, normal.height() / 2)}) {
        QCOMPARE(qGray(turned.pixel(p)), 255 - qGray(normal.pixel(p)));
    }
    cursor_->setInvertedGrey(false);
}

void TestSliceViewTools::rightClickOpensMenuAndKeepsWindow() {
    SliceView* v = view(Orientation::Axial);
    QTest::mouseClick(v, Qt::RightButton, Qt::NoModifier, QPoint(100, 100));
    QCOMPARE(cursor_->windowWidth(), 400.0);
    QMenu* menu = v->findChild<QMenu*>();
    QVERIFY(menu);
    QTRY_VERIFY(menu->isVisible());
    menu->close();
}

void TestSliceViewTools::ctrlWheelZoomsAboutMouse() {
    SliceView* v = view(Orientation::Axial);
    const double before = v->plane().pixelSize;
    const QPointF mouse(60.0, 50.0);
    const glm::dvec3 under = v->plane().pointAt(mouse.x(), mouse.y());
    wheel(v, 120, mouse, Qt::ControlModifier);
    QVERIFY(near(v->zoom(), 1.25));
    QVERIFY(near(v->plane().pixelSize, before / 1.25));
    // The point under the mouse stays there.
    const glm::dvec3 after = v->plane().pointAt(mouse.x(), mouse.y());
    QVERIFY2(near(glm::distance(after, under), 0.0, 1e-9), qPrintable(text(after - under)));
    // The slice did not move.
    QVERIFY(near(v->plane().distance(under), 0.0));
    wheel(v, -360, mouse, Qt::ControlModifier);
    QVERIFY(near(v->plane().pixelSize, before * 1.25 * 1.25));
    // A plain wheel still scrolls slices and leaves the zoom.
    wheel(v, 120, mouse, Qt::NoModifier);
    QVERIFY(near(v->zoom(), 1.0 / (1.25 * 1.25)));
    QTest::keyClick(v, Qt::Key_R);
    QCOMPARE(v->zoom(), 1.0);
    QVERIFY(near(v->plane().pixelSize, before));
}

void TestSliceViewTools::middleDragPans() {
    SliceView* v = view(Orientation::Coronal);
    const glm::dvec3 grabbed = v->plane().pointAt(100.0, 100.0);
    const glm::dvec3 crosshair = cursor_->point();
    QTest::mousePress(v, Qt::MiddleButton, Qt::NoModifier, QPoint(100, 100));
    QTest::mouseMove(v, QPoint(130, 80));
    QTest::mouseRelease(v, Qt::MiddleButton, Qt::NoModifier, QPoint(130, 80));
    QVERIFY(near(glm::distance(v->plane().pointAt(130.0, 80.0), grabbed), 0.0, 1e-9));
    QCOMPARE(v->pan(), glm::dvec2(-30.0, 20.0) * v->plane().pixelSize);
    // Panning moves neither the crosshair nor the other views.
    QCOMPARE(cursor_->point(), crosshair);
    QCOMPARE(view(Orientation::Axial)->pan(), glm::dvec2(0.0));
}

void TestSliceViewTools::slabKeysThickenThePlane() {
    SliceView* v = view(Orientation::Coronal);
    QTest::keyClick(v, Qt::Key_S);
    QCOMPARE(v->slabMode(), SlabMode::Mip);
    QCOMPARE(v->slabThickness(), 10.0);
    QCOMPARE(v->plane().slabThickness, 10.0);
    QTest::keyClick(v, Qt::Key_BracketRight);
    QCOMPARE(v->slabThickness(), 15.0);
    QTest::keyClick(v, Qt::Key_BracketLeft);
    QTest::keyClick(v, Qt::Key_BracketLeft);
    QCOMPARE(v->slabThickness(), 5.0);
    // The field grows 10 per mm along y (the coronal normal): over a 5 mm slab the MIP
    // is the centre value + 25, the MinIP - 25, the average the centre value.
    const QPointF centre = QPointF(120.0, 100.0);
    const double thin = field(v->plane().pointAt(centre.x(), centre.y()));
    QVERIFY2(near(v->valueAt(centre), thin + 25.0, 1e-2),
             qPrintable(QString::number(v->valueAt(centre) - thin)));
    QTest::keyClick(v, Qt::Key_S);
    QCOMPARE(v->slabMode(), SlabMode::MinIp);
    QVERIFY(near(v->valueAt(centre), thin - 25.0, 1e-2));
    QTest::keyClick(v, Qt::Key_S);
    QCOMPARE(v->slabMode(), SlabMode::Average);
    QVERIFY(near(v->valueAt(centre), thin, 1e-2));
    QTest::keyClick(v, Qt::Key_S);
    QCOMPARE(v->slabThickness(), 0.0);
    QVERIFY(near(v->valueAt(centre), thin, 1e-2));
    // Only this view is thick.
    QCOMPARE(view(Orientation::Axial)->slabThickness(), 0.0);
}

void TestSliceViewTools::distanceBetweenTwoClicks() {
    // Axial: the volume is 28 x 27 mm in x and y; in 240 x 200 pixels that is
    // max(28/240, 27/200) = 0.135 mm per pixel, so 100 pixels across read 13.5 mm.
    SliceView* axial = view(Orientation::Axial);
    const glm::dvec3 crosshair = cursor_->point();
    QTest::keyClick(axial, Qt::Key_D);
    QCOMPARE(axial->tool(), SliceView::Tool::Distance);
    QTest::mouseClick(axial, Qt::LeftButton, Qt::NoModifier, QPoint(50, 60));
    QVERIFY(measured().empty());
    QTest::mouseClick(axial, Qt::LeftButton, Qt::NoModifier, QPoint(150, 60));
    QCOMPARE(measured().size(), std::size_t(1));
    const double mm = measurementLengthMm(measured()[0]);
    QVERIFY2(near(mm, 13.5, 1e-9), qPrintable(QString::number(mm)));
    // Measuring leaves the crosshair alone.
    QCOMPARE(cursor_->point(), crosshair);

    // Coronal: 28 x 40 mm (x, z) -> 0.2 mm per pixel; a diagonal of 30 and 40 pixels is 10 mm.
    SliceView* coronal = view(Orientation::Coronal);
    QTest::keyClick(coronal, Qt::Key_D);
    QTest::mouseClick(coronal, Qt::LeftButton, Qt::NoModifier, QPoint(100, 50));
    QTest::mouseClick(coronal, Qt::LeftButton, Qt::NoModifier, QPoint(130, 90));
    QVERIFY(near(measurementLengthMm(measured().at(1)), 10.0, 1e-9));
    // Zoomed in, the same pixels are fewer millimetres.
    wheel(coronal, 120, QPointF(120, 100), Qt::ControlModifier);
    QTest::mouseClick(coronal, Qt::LeftButton, Qt::NoModifier, QPoint(100, 50));
    QTest::mouseClick(coronal, Qt::LeftButton, Qt::NoModifier, QPoint(130, 90));
    QVERIFY(near(measurementLengthMm(measured().at(2)), 8.0, 1e-9));
    // Delete removes the selected one: the last drawn.
    QCOMPARE(measurements_->selected(), measured().at(2).id);
    QTest::keyClick(coronal, Qt::Key_Delete);
    QCOMPARE(measured().size(), std::size_t(2));
    QTest::keyClick(coronal, Qt::Key_Escape);
    QCOMPARE(coronal->tool(), SliceView::Tool::Crosshair);
}

void TestSliceViewTools::distanceByDrag() {
    SliceView* axial = view(Orientation::Axial);
    QTest::keyClick(axial, Qt::Key_D);
    QTest::mousePress(axial, Qt::LeftButton, Qt::NoModifier, QPoint(40, 40));
    QTest::mouseMove(axial, QPoint(100, 80));
    QTest::mouseRelease(axial, Qt::LeftButton, Qt::NoModifier, QPoint(100, 120));
    QCOMPARE(measured().size(), std::size_t(1));
    QVERIFY(near(measurementLengthMm(measured()[0]), 100.0 * 0.135, 1e-9));
}

void TestSliceViewTools::ellipseRoiOverUniformRegion() {
    setVolume(makeVolume(true));
    SliceView* axial = view(Orientation::Axial);
    // The 35 HU block spans x -7..6.3 mm and y -5.8..5.9 mm; its pixels (0.135 mm):
    const glm::dvec2 a = axial->plane().pixelOf({-5.0, -4.0, 0.0});
    const glm::dvec2 b = axial->plane().pixelOf({5.0, 4.0, 0.0});
    QTest::keyClick(axial, Qt::Key_E);
    QTest::mousePress(axial, Qt::LeftButton, Qt::NoModifier, QPoint(int(a.x), int(a.y)));
    QTest::mouseMove(axial, QPoint(int(b.x), int(b.y)));
    QTest::mouseRelease(axial, Qt::LeftButton, Qt::NoModifier, QPoint(int(b.x), int(b.y)));
    QCOMPARE(measured().size(), std::size_t(1));
    const Measurement m = measured()[0];
    QCOMPARE(m.unit, std::string("HU"));
    QCOMPARE(m.statistics.mean, 35.0);
    QCOMPARE(m.statistics.standardDeviation, 0.0);
    const double ru = 0.5 * (int(b.x) - int(a.x)) * 0.135;
    const double rv = 0.5 * (int(b.y) - int(a.y)) * 0.135;
    QVERIFY(near(measurementEllipse(m).radiusU, ru, 1e-9));
    QVERIFY(near(m.statistics.areaMm2, std::numbers::pi * ru * rv, 1e-6));
    QVERIFY(m.statistics.samples > 100);

    // One over the block's edge mixes 35 and -1000 HU.
    const glm::dvec2 c = axial->plane().pixelOf({0.0, 0.0, 0.0});
    const glm::dvec2 d = axial->plane().pixelOf({12.0, 3.0, 0.0});
    QTest::mouseClick(axial, Qt::LeftButton, Qt::NoModifier, QPoint(int(c.x), int(c.y)));
    QTest::mouseClick(axial, Qt::LeftButton, Qt::NoModifier, QPoint(int(d.x), int(d.y)));
    QCOMPARE(measured().size(), std::size_t(2));
    const RoiStatistics& mixed = measured()[1].statistics;
    QVERIFY(mixed.mean < 30.0 && mixed.mean > -1000.0);
    QVERIFY(mixed.standardDeviation > 10.0);
}

void TestSliceViewTools::shiftDragMakesObliquePlanes() {
    SliceView* axial = view(Orientation::Axial);
    SliceView* coronal = view(Orientation::Coronal);
    const glm::dvec3 point = cursor_->point();
    const glm::dvec2 c = axial->plane().pixelOf(point);
    const QPointF centre(c.x, c.y);
    // From 3 o'clock to 30 degrees below it (screen down is +v): 30 degrees from u to v.
    const double angle = std::numbers::pi / 6.0;
    QTest::mousePress(axial, Qt::LeftButton, Qt::ShiftModifier,
                      (centre + QPointF(60, 0)).toPoint());
    const QPointF end = centre + 60.0 * QPointF(std::cos(angle), std::sin(angle));
    QTest::mouseMove(axial, end.toPoint());
    QTest::mouseRelease(axial, Qt::LeftButton, Qt::ShiftModifier, end.toPoint());
    const double turned =
        std::atan2(std::round(end.y()) - c.y, std::round(end.x()) - c.x) -
        std::atan2(std::round(centre.y()) - c.y, std::round(centre.x() + 60) - c.x);
    // The axial plane stays; the coronal one turned about the axial normal (+z).
    QCOMPARE(axial->plane().normal(), glm::dvec3(0.0, 0.0, 1.0));
    const glm::dvec3 wantNormal(-std::sin(turned), std::cos(turned), 0.0);
    QVERIFY2(near(glm::distance(coronal->plane().normal(), wantNormal), 0.0, 1e-9),
             qPrintable(text(coronal->plane().normal())));
    QVERIFY(std::abs(turned - angle) < 0.03);
    QCOMPARE(cursor_->point(), point);
    // The orientation letters follow: right of the coronal view is now left-posterior.
    QCOMPARE(QString::fromStdString(directionLabel(coronal->plane().u)), QStringLiteral("LP"));
    QCOMPARE(QString::fromStdString(directionLabel(-coronal->plane().u)), QStringLiteral("RA"));

    // Reslicing: the oblique plane samples the field at known patient points.
    const SlicePlane plane = coronal->plane();
    for (const glm::dvec2 offset :
         {glm::dvec2(0, 0), glm::dvec2(-20, 10), glm::dvec2(15, -25), glm::dvec2(30, 40)}) {
        const glm::dvec2 px = glm::round(plane.pixelOf(point)) + offset;
        const glm::dvec3 p = plane.pointAt(px.x, px.y);
        const double got = coronal->valueAt(QPointF(px.x + 0.5, px.y + 0.5));
        QVERIFY2(near(got, field(p), 2e-3),
                 qPrintable(
                     QStringLiteral("at %1: got %2, want %3").arg(text(p)).arg(got).arg(field(p))));
    }
    // The crosshair point lies in every plane; O takes the planes back to standard.
    QVERIFY(near(plane.distance(point), 0.0));
    QVERIFY(near(view(Orientation::Sagittal)->plane().distance(point), 0.0));
    QTest::keyClick(coronal, Qt::Key_O);
    QCOMPARE(coronal->plane().normal(), glm::dvec3(0.0, 1.0, 0.0));
}

void TestSliceViewTools::cineKeyPlaysThroughSlices() {
    SliceView* axial = view(Orientation::Axial);
    const double start = axial->slicePosition();
    QTest::keyClick(axial, Qt::Key_C);
    QVERIFY(axial->cineRunning());
    QTRY_VERIFY_WITH_TIMEOUT(axial->slicePosition() >= start + 2 * 2.0 - 1e-9, 3000);
    QTest::keyClick(axial, Qt::Key_C);
    QVERIFY(!axial->cineRunning());
    const double stopped = axial->slicePosition();
    QTest::qWait(3 * axial->cineIntervalMs());
    QCOMPARE(axial->slicePosition(), stopped);
    // It wraps: from the last slice it goes on from the first.
    wheel(axial, 120 * 100, QPointF(120, 100), Qt::NoModifier);
    const double last = axial->slicePosition();
    axial->setCineRunning(true);
    QTRY_VERIFY_WITH_TIMEOUT(axial->slicePosition() < last - 1.0, 3000);
    axial->setCineRunning(false);
}

void TestSliceViewTools::overlayHelpers() {
    QCOMPARE(scaleBarLengthMm(0.135, 60.0), 5.0); // 8.1 mm fits -> 5 mm
    QCOMPARE(scaleBarLengthMm(0.2, 60.0), 10.0);  // 12 mm -> 10 mm
    QCOMPARE(scaleBarLengthMm(1.0, 60.0), 50.0);  // 60 mm -> 50 mm
    QCOMPARE(scaleBarLengthMm(1.0, 25.0), 20.0);  // 25 mm -> 20 mm
    QCOMPARE(scaleBarLengthMm(0.0, 60.0), 0.0);
    const QStringList lines = seriesOverlayLines(*view(Orientation::Axial)->volume());
    QCOMPARE(lines, (QStringList{"Doe^Jane", "ID P-0042", "2024-01-31", "CT Head 1.0 H30s"}));
    QVERIFY(seriesOverlayLines(SeriesInfo{}).isEmpty());
    // The scale bar and the series text are drawn: grabbing paints without trouble.
    QVERIFY(!view(Orientation::Axial)->grab().isNull());
}

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestSliceViewTools test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_slice_view_tools.moc"
