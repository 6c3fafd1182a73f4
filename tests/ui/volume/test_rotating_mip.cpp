// The 3D view's rotating MIP (ui/volume/RotatingMip) on the real widget, CPU backend,
// offscreen: the action (its tool button in the view's controls and its shortcut) sets MIP
// and turns the camera about the head-foot axis 10 degrees a frame, so a ball off the axis
// swings across the frames while staying at its height; a key or a click stops it. A PET
// series opens in MIP, inverted grey on white.
#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QSignalSpy>
#include <QTest>
#include <QToolButton>

#include <cmath>
#include <memory>
#include <vector>

#include "core/pet/PetProjection.h"
#include "core/scene/Turntable.h"
#include "core/scene/ViewFrame.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/ui/volume/BallVolume.h"
#include "ui/volume/RotatingMip.h"
#include "ui/volume/VolumeView.h"
#include "ui/volume/VolumeViewControls.h"

using namespace lucent;

namespace {

constexpr int kSize = 160;

// Centre of mass of the frame's brightness (red channel), in pixels.
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

struct Shown {
    double azimuth;
    QPointF ball;
};

// A PET series in SUVbw: a ball of 5 SUV (radius 6 voxels) in 0, 2 mm voxels.
std::shared_ptr<const Volume> petBall() {
    VolumeGeometry g;
    g.dims = {32, 32, 32};
    g.spacing = glm::dvec3(2.0);
    auto volume = std::make_shared<Volume>(g, VoxelType::Float32);
    for (int k = 0; k < 32; ++k) {
        for (int j = 0; j < 32; ++j) {
            for (int i = 0; i < 32; ++i) {
                volume->voxels<float>()[volume->linearIndex(i, j, k)] =
                    glm::length(glm::dvec3(i, j, k) - glm::dvec3(15.5)) <= 6.0 ? 5.0f : 0.0f;
            }
        }
    }
    volume->modality = "PT";
    PetDisplay pet;
    pet.suvFactor = 1e-4;
    pet.storedUnits = "BQML";
    volume->pet = pet;
    return volume;
}

} // namespace

class TestRotatingMip : public QObject {
    Q_OBJECT
    std::unique_ptr<VolumeView> view_;

    const ImageRGBA8& stillFrame() {
        QSignalSpy frames(view_.get(), &VolumeView::renderedFrame);
        view_->requestRender();
        if (!QTest::qWaitFor([&] { return !frames.isEmpty() && view_->lastFrameCurrent(); },
                             10000)) {
            qWarning("no frame within 10 s");
        }
        return view_->lastFrame();
    }

private slots:
    void init() {
        view_ = std::make_unique<VolumeView>(nullptr, VolumeView::Backend::Cpu);
        view_->resize(kSize, kSize);
        view_->show();
        view_->activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(view_.get()));
        // Off the head-foot axis along the patient's left (+x): it swings as the view turns.
        view_->setVolume(test::makeBall(glm::dvec3(22.0, 15.5, 15.5), 5.0));
        view_->setTransferFunction(test::whiteBall());
    }
    void cleanup() { view_.reset(); }

    void actionTurnsTheMipAboutTheHeadFootAxis() {
        VolumeViewControls controls(view_.get());
        RotatingMip* rotating = view_->rotatingMip();
        QToolButton* button = nullptr;
        for (QToolButton* b : controls.findChildren<QToolButton*>()) {
            button = b->defaultAction() == rotating->action() ? b : button;
        }
        QVERIFY(button != nullptr);
        Camera tilted;
        tilted.elevation = 30.0;
        tilted.panRight = 4.0;
        view_->setCamera(tilted);
        QCOMPARE(controls.modePicker()->currentIndex(), 0); // DVR

        std::vector<Shown> shown;
        connect(
            view_.get(), &VolumeView::renderedFrame, this,
            [&](const RenderStats&, bool interactive) {
                if (!interactive && rotating->running()) {
                    shown.push_back({view_->camera().azimuth, brightCentre(view_->lastFrame())});
                }
            });
        QTest::mouseClick(button, Qt::LeftButton);
        QVERIFY(rotating->running());
        QVERIFY(rotating->action()->isChecked());
        QCOMPARE(view_->mode(), RenderMode::Mip);
        QCOMPARE(controls.modePicker()->currentIndex(), 1);            // the controls follow: MIP
        QCOMPARE(view_->transferFunction().name, std::string("ball")); // not PET: kept
        QVERIFY(QTest::qWaitFor([&] { return rotating->frame() >= 9; }, 20000));
        // Each frame's camera: levelled, centred, 10 degrees on about +z (head up).
        const Camera c = view_->camera();
        QCOMPARE(c.elevation, 0.0);
        QCOMPARE(c.panRight, 0.0);
        QVERIFY(std::abs(c.azimuth - 10.0 * (rotating->frame() % kRotatingMipFrames)) < 1e-9);
        const ViewFrame f = makeViewFrame(view_->volume()->geometry(), c, kSize, kSize);
        QVERIFY(glm::length(f.up - glm::dvec3(0, 0, 1)) < 1e-12);

        // Stopped by a key; the camera stays where it was.
        QTest::keyClick(view_.get(), Qt::Key_Escape);
        QVERIFY(!rotating->running());
        QVERIFY(!rotating->action()->isChecked());
        const double stoppedAt = view_->camera().azimuth;
        QTest::qWait(3 * kRotatingMipFrameMs);
        QCOMPARE(view_->camera().azimuth, stoppedAt);
        QCOMPARE(view_->mode(), RenderMode::Mip);

        // The frames: the ball's horizontal offset from the middle goes as cos(azimuth)
        // (it lies on +x, the screen's right at azimuth 0), its height does not change.
        QVERIFY2(shown.size() >= 4, qPrintable(QString::number(shown.size())));
        QCOMPARE(shown.front().azimuth, 0.0);
        const double reach = shown.front().ball.x() - kSize / 2.0;
        QVERIFY2(reach > 10.0, qPrintable(QString::number(reach)));
        int distinct = 0;
        for (const Shown& s : shown) {
            const double want = reach * std::cos(glm::radians(s.azimuth));
            QVERIFY2(std::abs((s.ball.x() - kSize / 2.0) - want) < 1.5,
                     qPrintable(QString("azimuth %1: x %2, want %3")
                                    .arg(s.azimuth)
                                    .arg(s.ball.x() - kSize / 2.0)
                                    .arg(want)));
            QVERIFY(std::abs(s.ball.y() - shown.front().ball.y()) < 0.5);
            distinct += std::abs(s.ball.x() - shown.front().ball.x()) > 1.0 ? 1 : 0;
        }
        QVERIFY(distinct >= 3);
    }

    // The shortcut starts and stops it; a click in the view stops it too.
    void shortcutAndClick() {
        RotatingMip* rotating = view_->rotatingMip();
        QCOMPARE(rotating->action()->shortcut(), QKeySequence(QStringLiteral("Ctrl+Shift+R")));
        QTest::keyClick(view_.get(), Qt::Key_R, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(rotating->running());
        QTest::keyClick(view_.get(), Qt::Key_R, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(!rotating->running());
        rotating->action()->trigger();
        QVERIFY(rotating->running());
        QTest::mousePress(view_.get(), Qt::LeftButton, {}, QPoint(80, 80));
        QVERIFY(!rotating->running());
        QTest::mouseRelease(view_.get(), Qt::LeftButton, {}, QPoint(80, 80));
        // Another camera stops it too (Reset view).
        rotating->start();
        view_->resetCamera();
        QVERIFY(!rotating->running());
    }

    // PET in SUVbw opens in MIP, inverted grey on white: no uptake white, 5 SUV (of the
    // window's 6) at 1 - 5/6 of white; the rotating MIP keeps that look.
    void petShownInvertedGrey() {
        view_->setVolume(petBall());
        QCOMPARE(view_->mode(), RenderMode::Mip);
        const TransferFunction& tf = view_->transferFunction();
        QCOMPARE(tf.name, std::string(kPetMipTransferFunctionName));
        QCOMPARE(tf.opacity.front().value, 0.0); // the 0 to 6 SUV window
        QCOMPARE(tf.opacity.back().value, 6.0);
        QCOMPARE(view_->description().background, glm::dvec3(1.0));
        const ImageRGBA8& f = stillFrame();
        QCOMPARE(int(f.pixels[f.offset(2, 2)]), 255);
        const int middle = f.pixels[f.offset(kSize / 2, kSize / 2)];
        QVERIFY2(std::abs(middle - 255.0 / 6.0) < 3.0, qPrintable(QString::number(middle)));
        view_->rotatingMip()->start();
        QCOMPARE(view_->transferFunction().name, std::string(kPetMipTransferFunctionName));
        view_->rotatingMip()->stop();
        // Another transfer function is shown on black again.
        view_->setTransferFunction(test::whiteBall());
        QCOMPARE(view_->description().background, glm::dvec3(0.0));
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestRotatingMip test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_rotating_mip.moc"
