// The Surface panel on real widgets and a real OpenGL context (llvmpipe under
// Xvfb): a computed surface is shown in the 3D view (coloured by its SVR
// field, with a colour bar; plain; alone), exported, cleared; a long
// computation is cancelled; on the CPU renderer the view says the surface is
// not drawn.
#include <QApplication>
#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include <random>

#include "core/image/ImageMetrics.h"
#include "tests/support/XvfbRelaunch.h"
#include "tests/ui/volume/BallVolume.h"
#include "ui/volume/SurfacePanel.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;
using lucent::test::makeBall;

namespace {

// Noise: a surface of millions of triangles, for the cancel test.
std::shared_ptr<const Volume> noise() {
    VolumeGeometry g;
    g.dims = {128, 128, 128};
    auto volume = std::make_shared<Volume>(g, VoxelType::Int16);
    std::mt19937 random(7);
    std::uniform_int_distribution<int> value(-100, 100);
    for (auto& v : volume->voxels<std::int16_t>()) {
        v = std::int16_t(value(random));
    }
    return volume;
}

bool waitComputed(QSignalSpy& spy, int timeoutMs = 60000) {
    return spy.size() > 0 || spy.wait(timeoutMs);
}

} // namespace

class TestSurfacePanel : public QObject {
    Q_OBJECT

    std::unique_ptr<VolumeView> view_;
    std::unique_ptr<SurfacePanel> panel_;
    QTemporaryDir tmp_;

    ImageRGBA8 frameNow() {
        view_->requestRender();
        QTest::qWait(50);
        QCoreApplication::processEvents();
        return view_->lastFrame();
    }

private slots:
    void init() {
        view_ = std::make_unique<VolumeView>();
        view_->resize(160, 128);
        view_->setVolume(makeBall());
        view_->show();
        QVERIFY(QTest::qWaitForWindowExposed(view_.get()));
        panel_ = std::make_unique<SurfacePanel>(view_.get());
        QVERIFY2(view_->backend() == VolumeView::Backend::Gpu, qPrintable(view_->notice()));
    }
    void cleanup() {
        panel_.reset();
        view_.reset();
    }

    void aComputedSurfaceIsShownAndExported() {
        const ImageRGBA8 before = frameNow();
        panel_->isoValue()->setValue(500.0);
        panel_->radius()->setValue(3.0);
        QSignalSpy computed(panel_.get(), &SurfacePanel::computed);
        panel_->computeOrCancel();
        QVERIFY(waitComputed(computed));
        QVERIFY2(computed.first().first().toBool(), qPrintable(panel_->status()));
        QVERIFY2(panel_->status().contains("closed") && !panel_->status().contains("NOT"),
                 qPrintable(panel_->status()));
        QVERIFY2(panel_->status().contains("SVR at R = 3 mm"), qPrintable(panel_->status()));
        const auto display = view_->surfaceDisplay();
        QVERIFY(display && display->mesh && display->field);
        QCOMPARE(display->field->size(), display->mesh->vertices.size());
        QVERIFY(display->fieldLo < display->fieldHi);
        // A ball of radius 10 mm: SVR near 12a / (R (8a - 3R)) = 0.56 /mm everywhere.
        const double expected = 12.0 * 10.0 / (3.0 * (80.0 - 9.0));
        QVERIFY2(std::abs(display->fieldLo / expected - 1.0) < 0.1 &&
                     std::abs(display->fieldHi / expected - 1.0) < 0.1,
                 qPrintable(QString("%1 .. %2").arg(display->fieldLo).arg(display->fieldHi)));
        const ImageRGBA8 shown = frameNow();
        QVERIFY(psnr(before, shown) < 30.0); // the surface is drawn

        // Plain, then alone: the display follows the check boxes.
        panel_->colourByField()->setChecked(false);
        QVERIFY(view_->surfaceDisplay() && !view_->surfaceDisplay()->field);
        panel_->showVolume()->setChecked(false);
        QVERIFY(!view_->surfaceDisplay()->showVolume);
        const ImageRGBA8 alone = frameNow();
        QVERIFY(psnr(alone, shown) < 40.0);

        QVERIFY(panel_->exportTo(tmp_.filePath("ball.ply")));
        QVERIFY(QFileInfo(tmp_.filePath("ball.ply")).size() > 1000);
        QVERIFY(!panel_->exportTo(tmp_.filePath("no/such/folder/ball.stl")));
        QVERIFY2(panel_->status().contains("Export failed"), qPrintable(panel_->status()));

        panel_->clear();
        QVERIFY(!view_->surfaceDisplay());
        QVERIFY(psnr(frameNow(), before) > 40.0);
    }

    void aLongComputationIsCancelled() {
        view_->setVolume(noise());
        panel_->isoValue()->setValue(0.0);
        panel_->radius()->setValue(30.0);
        QSignalSpy computed(panel_.get(), &SurfacePanel::computed);
        panel_->computeOrCancel();
        QVERIFY(panel_->computing());
        panel_->computeOrCancel(); // Cancel
        QVERIFY(waitComputed(computed, 30000));
        QCOMPARE(computed.first().first().toBool(), false);
        QCOMPARE(panel_->status(), QString("Cancelled."));
        QVERIFY(!view_->surfaceDisplay());
    }

    void anIsoOutsideTheValuesIsRefused() {
        // The spin box keeps the iso within the volume's values; the edge is allowed.
        panel_->isoValue()->setValue(1e9);
        QCOMPARE(panel_->isoValue()->value(), 1000.0);
    }

    void theCpuRendererSaysItDoesNotDrawIt() {
        VolumeView cpu(nullptr, VolumeView::Backend::Cpu);
        cpu.setVolume(makeBall());
        SurfacePanel panel(&cpu);
        panel.radius()->setValue(0.0);
        QSignalSpy computed(&panel, &SurfacePanel::computed);
        panel.computeOrCancel();
        QVERIFY(waitComputed(computed));
        QVERIFY(computed.first().first().toBool());
        QVERIFY2(cpu.notice().contains("GPU renderer only"), qPrintable(cpu.notice()));
    }
};

int main(int argc, char** argv) {
    if (const int status = lucent::test::relaunchUnderXvfbWhenHeadless(argc, argv); status >= 0) {
        return status;
    }
    QSurfaceFormat::setDefaultFormat(VolumeView::surfaceFormat());
    QApplication app(argc, argv);
    TestSurfacePanel test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_surface_panel.moc"
