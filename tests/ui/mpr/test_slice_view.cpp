// The MPR view widget on a synthetic volume: wheel, window/level drag, and the
// crosshair that links the three orientations.
#include <QApplication>
#include <QTest>
#include <QWheelEvent>

#include <cmath>
#include <memory>

#include "tests/support/OffscreenPlatform.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SliceView.h"

using namespace lucent;

namespace {

// value = x + 10 y + 100 z of the voxel's LPS position (mm)
std::shared_ptr<const Volume> makeVolume() {
    VolumeGeometry g;
    g.dims = {40, 30, 20};
    g.spacing = {0.7, 0.9, 2.0};
    g.origin = {-14.0, -13.0, 50.0};
    auto volume = std::make_shared<Volume>(g, VoxelType::Float32);
    auto voxels = volume->voxels<float>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const glm::dvec3 p = g.toPatient(glm::dvec3(i, j, k));
                voxels[volume->linearIndex(i, j, k)] =
                    static_cast<float>(p.x + 10 * p.y + 100 * p.z);
            }
        }
    }
    volume->modality = "CT";
    return volume;
}

void wheel(QWidget* w, int delta) {
    const QPointF pos(w->width() / 2.0, w->height() / 2.0);
    QWheelEvent event(pos, w->mapToGlobal(pos), QPoint(), QPoint(0, delta), Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(w, &event);
}

bool near(double a, double b) {
    return std::abs(a - b) < 1e-9;
}

} // namespace

class TestSliceView : public QObject {
    Q_OBJECT

private slots:
    void init();
    void cleanup();
    void wheelMovesOneSlice_data();
    void wheelMovesOneSlice();
    void rightDragChangesWindow();
    void clickMovesCrosshairAndLinkedViews();
    void imageFollowsConventions();

private:
    SliceView* view(Orientation o) { return views_[static_cast<int>(o)].get(); }

    std::shared_ptr<const Volume> volume_ = makeVolume();
    std::unique_ptr<MprCursor> cursor_;
    std::unique_ptr<SliceView> views_[3];
};

void TestSliceView::init() {
    cursor_ = std::make_unique<MprCursor>();
    cursor_->setPoint(volume_->geometry().toPatient(glm::dvec3(volume_->dims() / 2)));
    cursor_->setWindow(40.0, 400.0);
    for (const Orientation o : {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
        auto& v = views_[static_cast<int>(o)];
        v = std::make_unique<SliceView>(o, cursor_.get());
        v->resize(240, 200);
        v->setVolume(volume_);
        v->show();
        QVERIFY(QTest::qWaitForWindowExposed(v.get()));
    }
}

void TestSliceView::cleanup() {
    for (auto& v : views_) {
        v.reset();
    }
    cursor_.reset();
}

void TestSliceView::wheelMovesOneSlice_data() {
    QTest::addColumn<int>("orientation");
    QTest::addColumn<int>("axis");    // the LPS axis the plane moves along
    QTest::addColumn<double>("step"); // mm along that axis for one notch forward
    QTest::newRow("axial") << int(Orientation::Axial) << 2 << 2.0;        // towards the head
    QTest::newRow("coronal") << int(Orientation::Coronal) << 1 << 0.9;    // towards the back
    QTest::newRow("sagittal") << int(Orientation::Sagittal) << 0 << -0.7; // towards the right
}

void TestSliceView::wheelMovesOneSlice() {
    QFETCH(int, orientation);
    QFETCH(int, axis);
    QFETCH(double, step);
    SliceView* v = view(static_cast<Orientation>(orientation));
    QCOMPARE(v->sliceStep(), std::abs(step));
    const glm::dvec3 before = cursor_->point();
    const glm::dvec3 centreBefore = v->plane().centre;
    const double positionBefore = v->slicePosition();

    wheel(v, 120);
    glm::dvec3 moved = cursor_->point() - before;
    QVERIFY(near(moved[axis], step));
    QVERIFY(near(glm::length(moved), std::abs(step)));
    QVERIFY(near(glm::length(v->plane().centre - centreBefore), std::abs(step)));
    QVERIFY(near(v->slicePosition() - positionBefore, step));

    // Half notches add up; two back notches go back past the start.
    wheel(v, 60);
    QVERIFY(near(cursor_->point()[axis] - before[axis], step));
    wheel(v, 60);
    QVERIFY(near(cursor_->point()[axis] - before[axis], 2 * step));
    wheel(v, -360);
    moved = cursor_->point() - before;
    QVERIFY(near(moved[axis], -step));

    // The plane stops at the last slice.
    wheel(v, 120 * 1000);
    const glm::dvec3 ijk = volume_->geometry().toIndex(cursor_->point());
    const double last = step > 0 ? volume_->dims()[axis] - 1.0 : 0.0;
    QVERIFY2(near(ijk[axis], last), qPrintable(QString::number(ijk[axis])));
}

void TestSliceView::rightDragChangesWindow() {
    SliceView* v = view(Orientation::Coronal);
    const QPoint start(100, 100);
    QTest::mousePress(v, Qt::RightButton, Qt::NoModifier, start);
    QTest::mouseMove(v, start + QPoint(30, -20));
    QCOMPARE(cursor_->windowWidth(), 430.0);
    QCOMPARE(cursor_->windowCenter(), 20.0);
    QTest::mouseRelease(v, Qt::RightButton, Qt::NoModifier, start + QPoint(-50, 15));
    QCOMPARE(cursor_->windowWidth(), 350.0);
    QCOMPARE(cursor_->windowCenter(), 55.0);
    // Moving without a button pressed leaves the window alone.
    QTest::mouseMove(v, start + QPoint(80, 80));
    QCOMPARE(cursor_->windowWidth(), 350.0);

    // Proportional: 2.5 units per pixel.
    cursor_->setWindowStep(2.5);
    QTest::mousePress(v, Qt::RightButton, Qt::NoModifier, start);
    QTest::mouseRelease(v, Qt::RightButton, Qt::NoModifier, start + QPoint(10, 4));
    QCOMPARE(cursor_->windowWidth(), 375.0);
    QCOMPARE(cursor_->windowCenter(), 65.0);
    // The crosshair did not move.
    QCOMPARE(cursor_->point(), volume_->geometry().toPatient(glm::dvec3(volume_->dims() / 2)));
}

void TestSliceView::clickMovesCrosshairAndLinkedViews() {
    SliceView* axial = view(Orientation::Axial);
    SliceView* coronal = view(Orientation::Coronal);
    SliceView* sagittal = view(Orientation::Sagittal);
    const double axialBefore = axial->slicePosition();
    const glm::dvec3 coronalBefore = coronal->plane().centre;
    const glm::dvec3 sagittalBefore = sagittal->plane().centre;

    const QPoint click(150, 60);
    const glm::dvec3 expected = axial->plane().pointAt(click.x(), click.y());
    QTest::mouseClick(axial, Qt::LeftButton, Qt::NoModifier, click);
    QCOMPARE(cursor_->point(), expected);

    // The axial plane stays; the coronal plane moves to the clicked y, the sagittal to its x.
    QVERIFY(near(axial->slicePosition(), axialBefore));
    QVERIFY(near(coronal->plane().distance(expected), 0.0));
    QVERIFY(near(coronal->plane().centre.y, expected.y));
    QVERIFY(near(coronal->slicePosition(), expected.y));
    QVERIFY(!near(coronal->plane().centre.y, coronalBefore.y));
    QVERIFY(near(sagittal->plane().distance(expected), 0.0));
    QVERIFY(near(sagittal->plane().centre.x, expected.x));
    QVERIFY(near(sagittal->slicePosition(), expected.x));
    QVERIFY(!near(sagittal->plane().centre.x, sagittalBefore.x));
    // In-plane, the other views stay centred on the volume.
    QVERIFY(near(coronal->plane().centre.x, coronalBefore.x));
    QVERIFY(near(coronal->plane().centre.z, coronalBefore.z));

    // The crosshair in the coronal view sits where the clicked point projects.
    const glm::dvec2 px = coronal->plane().pixelOf(expected);
    QVERIFY(near(coronal->plane().pointAt(px.x, px.y).x, expected.x));
    QVERIFY(near(coronal->plane().pointAt(px.x, px.y).z, expected.z));
}

void TestSliceView::imageFollowsConventions() {
    // Centred on the field's value at the crosshair: x + 10 y + 100 z.
    const glm::dvec3 c = cursor_->point();
    cursor_->setWindow(c.x + 10 * c.y + 100 * c.z, 400.0);
    const QImage axial = view(Orientation::Axial)->image();
    QCOMPARE(axial.size(), QSize(240, 200));
    // Down is posterior (+y): brighter; right is left (+x): brighter.
    QVERIFY(qGray(axial.pixel(120, 120)) > qGray(axial.pixel(120, 80)));
    const QImage coronal = view(Orientation::Coronal)->image();
    // Down is inferior: darker.
    QVERIFY(qGray(coronal.pixel(120, 130)) < qGray(coronal.pixel(120, 70)));
    // Outside the volume is black.
    QCOMPARE(qGray(coronal.pixel(0, 0)), 0);
    const QImage grab = view(Orientation::Sagittal)->grab().toImage();
    QVERIFY(!grab.isNull());
}

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestSliceView test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_slice_view.moc"
