// The 3D view's camera and clip tools on the real widget (CPU backend,
// offscreen): a middle-drag pans the camera so that the picture follows the
// mouse; Shift+wheel moves the eye into the volume; B shows the clip box, and
// dragging a face handle moves that face by the voxels the mouse travelled
// along the face's axis, re-rendering what the clip leaves.
#include <QApplication>
#include <QCheckBox>
#include <QSignalSpy>
#include <QSlider>
#include <QTest>
#include <QWheelEvent>

#include <cmath>
#include <functional>
#include <memory>

#include "tests/support/OffscreenPlatform.h"
#include "tests/ui/volume/BallVolume.h"
#include "ui/volume/VolumeView.h"
#include "ui/volume/VolumeViewControls.h"

using namespace lucent;
using lucent::test::makeBall;

namespace {

constexpr int kSize = 160;

// Centre of mass of the frame's brightness (a white ball on black), in pixels.
QPointF brightCentre(const ImageRGBA8& f) {
    double sum = 0.0, x = 0.0, y = 0.0;
    for (int py = 0; py < f.height; ++py) {
        for (int px = 0; px < f.width; ++px) {
            const double a = f.pixels[f.offset(px, py)] / 255.0;
            sum += a;
            x += a * (px + 0.5);
            y += a * (py + 0.5);
        }
    }
    return sum > 0.0 ? QPointF(x / sum, y / sum) : QPointF(-1, -1);
}

double brightness(const ImageRGBA8& f) {
    double sum = 0.0;
    for (std::size_t n = 0; n < f.pixels.size(); n += 4) {
        sum += f.pixels[n] / 255.0;
    }
    return sum;
}

void drag(QWidget* w, Qt::MouseButton button, QPoint from, QPoint to) {
    QTest::mousePress(w, button, {}, from);
    QTest::mouseMove(w, from + (to - from) / 2);
    QTest::mouseMove(w, to);
    QTest::mouseRelease(w, button, {}, to);
}

} // namespace

class TestVolumeViewTools : public QObject {
    Q_OBJECT
    std::unique_ptr<VolumeView> view_;

    // The still frame that follows `action` (the CPU backend renders from the
    // surface's paint, so the event loop must run).
    const ImageRGBA8& frameAfter(const std::function<void()>& action) {
        QSignalSpy frames(view_.get(), &VolumeView::renderedFrame);
        action();
        const bool still = QTest::qWaitFor(
            [&] {
                return !view_->interacting() && view_->lastFrameCurrent() && !frames.isEmpty() &&
                       !frames.last().at(1).toBool();
            },
            10000);
        if (!still) {
            qWarning("no still frame within 10 s");
        }
        return view_->lastFrame();
    }
    const ImageRGBA8& settledFrame() {
        return frameAfter([this] { view_->requestRender(); });
    }

private slots:
    void init() {
        view_ = std::make_unique<VolumeView>(nullptr, VolumeView::Backend::Cpu);
        view_->resize(kSize, kSize);
        view_->show();
        QVERIFY(QTest::qWaitForWindowExposed(view_.get()));
        view_->setVolume(makeBall());
        view_->setTransferFunction(test::whiteBall());
        settledFrame();
    }
    void cleanup() { view_.reset(); }

    void middleDragPansThePicture() {
        const QPointF before = brightCentre(settledFrame());
        QVERIFY(std::abs(before.x() - kSize / 2.0) < 1.0);
        const QPointF after = brightCentre(frameAfter([this] {
            drag(view_.get(), Qt::MiddleButton, {80, 80}, {100, 70});
        }));
        qInfo("ball centre %.2f,%.2f -> %.2f,%.2f", before.x(), before.y(), after.x(), after.y());
        // The ball's centre lies at the point looked at: it moves with the mouse.
        QVERIFY2(std::abs(after.x() - before.x() - 20.0) < 1.0, "x");
        QVERIFY2(std::abs(after.y() - before.y() + 10.0) < 1.0, "y");
        const QPointF reset = brightCentre(frameAfter([this] { view_->resetCamera(); }));
        QVERIFY(std::abs(reset.x() - before.x()) < 0.01);
    }

    void shiftWheelMovesTheEyeIntoTheVolume() {
        const double outside = brightness(settledFrame());
        const QPointF pos(kSize / 2.0, kSize / 2.0);
        for (int n = 0; n < 16; ++n) {
            QWheelEvent wheel(pos, view_->mapToGlobal(pos), QPoint(), QPoint(0, 120), Qt::NoButton,
                              Qt::ShiftModifier, Qt::NoScrollPhase, false);
            QApplication::sendEvent(view_.get(), &wheel);
        }
        const double distance = view_->camera().distance;
        qInfo("eye %.2f mm from the centre after 16 notches", distance);
        QVERIFY(distance > 0.0 && distance < 10.0); // inside the ball (radius 10)
        QCOMPARE(view_->camera().zoom, 1.0);
        const ImageRGBA8& inside = settledFrame();
        QVERIFY2(view_->notice().isEmpty() || !view_->notice().contains("Cannot"),
                 qPrintable(view_->notice()));
        // From inside the ball, every ray meets its far wall: the view is covered.
        QVERIFY2(brightness(inside) > 0.95 * kSize * kSize,
                 qPrintable(QString("covered %1 of %2").arg(brightness(inside)).arg(outside)));
    }

    void clipHandleDragMovesItsFace() {
        VolumeViewControls controls(view_.get());
        auto* box = controls.findChild<QCheckBox*>(QStringLiteral("clipHandles"));
        QVERIFY(box != nullptr && !box->isChecked());
        QVERIFY(!view_->clipHandlesShown());
        QTest::keyClick(view_.get(), Qt::Key_B);
        QVERIFY(view_->clipHandlesShown());
        QVERIFY(box->isChecked()); // the controls follow the key
        // Anterior view: i runs to the screen's right; its high face is the right handle.
        const ClipHandles handles = view_->clipHandles();
        const ClipHandle& right = handles[1];
        QVERIFY(right.visible && right.axis == 0 && right.side == 1);
        QVERIFY(right.perVoxel.x() > 1.0 && std::abs(right.perVoxel.y()) < 1e-6);
        const ClipHandle& top = handles[5]; // k high: the head end, up on screen
        QVERIFY(top.visible && top.perVoxel.y() < -1.0);

        QSignalSpy clipped(view_.get(), &VolumeView::clipBoxChanged);
        const double before = brightness(settledFrame());
        const QPoint from = right.screen.toPoint();
        const int moveVoxels = 12;
        const QPoint to = from - QPoint(int(std::lround(moveVoxels * right.perVoxel.x())), 0);
        const ImageRGBA8& after = frameAfter([&] { drag(view_.get(), Qt::LeftButton, from, to); });
        QVERIFY(clipped.count() >= 1);
        QCOMPARE(view_->camera().azimuth, 0.0); // a handle drag does not rotate
        const ClipBox clip = view_->clipBox();
        qInfo("clip i high %.1f after dragging %d voxels", clip.hi.x, moveVoxels);
        QVERIFY2(std::abs(clip.hi.x - (31.0 - moveVoxels)) <= 1.0,
                 qPrintable(QString::number(clip.hi.x)));
        QVERIFY(clip.lo.x == 0.0 && clip.lo.y == 0.0 && clip.hi.z == 31.0);
        QCOMPARE(controls.clipSlider(0, 1)->value(), int(clip.hi.x)); // the slider follows
        // The right part of the ball is cut away and the frame shows it.
        QVERIFY2(brightness(after) < 0.9 * before,
                 qPrintable(QString("%1 -> %2").arg(before).arg(brightness(after))));
        QVERIFY(brightCentre(after).x() < kSize / 2.0 - 2.0);

        // A drag past the opposite face stops there; a drag away from handles rotates.
        drag(view_.get(), Qt::LeftButton, view_->clipHandles()[1].screen.toPoint(), {2, 80});
        QCOMPARE(view_->clipBox().hi.x, view_->clipBox().lo.x);
        drag(view_.get(), Qt::LeftButton, {80, 150}, {100, 150});
        QVERIFY(view_->camera().azimuth != 0.0);
    }

    void handlesHiddenDoNotCatchTheMouse() {
        const ClipHandle right = view_->clipHandles()[1];
        drag(view_.get(), Qt::LeftButton, right.screen.toPoint(),
             right.screen.toPoint() - QPoint(30, 0));
        QCOMPARE(view_->clipBox().hi.x, 1e300); // untouched
        QVERIFY(view_->camera().azimuth != 0.0);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestVolumeViewTools test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_volume_view_tools.moc"
