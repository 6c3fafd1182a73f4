// Fusion in the viewport grid on the real CT: a copy of it in a new Frame of Reference is
// refused until registered, then fused through the registration's transform; the fused
// pixels are the map of the resampled overlay blended over the view's grey image; a grey
// checkerboard of the series over its registered copy is the series; the Fusion dock's
// controls change the look; the overlay stays when the viewport turns to another plane.
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QSignalSpy>
#include <QSlider>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "core/fusion/FusionCompositor.h"
#include "core/fusion/OverlayNudge.h"
#include "core/fusion/OverlayResampler.h"
#include "core/io/Catalog.h"
#include "core/store/StudyStore.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/RealData.h"
#include "ui/fusion/FusionPanel.h"
#include "ui/fusion/ViewportFusion.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SliceView.h"
#include "ui/viewports/GridShape.h"
#include "ui/viewports/SeriesLibrary.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportLinks.h"
#include "ui/viewports/ViewportWorkspace.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";

// The CT's voxels on a grid moved by `move` (the copy's anatomy at move(p) is the CT's at
// p), another series in another Frame of Reference.
std::shared_ptr<Volume> movedCopy(const Volume& ct, const glm::dmat4& move) {
    VolumeGeometry g = ct.geometry();
    g.origin = glm::dvec3(move * glm::dvec4(g.origin, 1.0));
    g.direction = glm::dmat3(move) * g.direction;
    auto copy = std::make_shared<Volume>(g, ct.type());
    std::memcpy(copy->bytes().data(), ct.bytes().data(), ct.byteCount());
    static_cast<SeriesInfo&>(*copy) = static_cast<const SeriesInfo&>(ct);
    copy->seriesUid = ct.seriesUid + ".2029";
    copy->frameOfReferenceUid = "2.25.2029";
    copy->description = "moved copy";
    return copy;
}

int channel(QRgb c, int ch) {
    return ch == 0 ? qRed(c) : (ch == 1 ? qGreen(c) : qBlue(c));
}

} // namespace

class TestViewportFusion : public QObject {
    Q_OBJECT

    std::shared_ptr<Volume> ct_;
    std::shared_ptr<Volume> moved_;
    glm::dmat4 move_{1.0};
    QTemporaryDir store_;

    // Each pixel of the blend is the colour map of the overlay's value there
    // (sampled by hand through the transform) over the grey.
    void verifyBlendedPixels(SliceView& view, const QImage& grey, const FusionStyle& style) {
        const QImage blended = view.fusedImage();
        const SlicePlane plane = view.plane();
        const glm::dmat4 toIndex = moved_->geometry().patientToIndex() * move_;
        int checked = 0;
        for (int y = 5; y < grey.height(); y += 37) {
            for (int x = 3; x < grey.width(); x += 29) {
                const double value =
                    sampleAt(*moved_, glm::dvec3(toIndex * glm::dvec4(plane.pointAt(x, y), 1.0)));
                if (std::isnan(value)) {
                    QCOMPARE(blended.pixel(x, y), grey.pixel(x, y));
                    continue;
                }
                QVERIFY(std::abs(view.overlayValueAt(QPointF(x, y)) - value) < 1e-2);
                const auto c = mapColour(style.colourMap, value, style.center, style.width);
                const int g = qRed(grey.pixel(x, y));
                for (int ch = 0; ch < 3; ++ch) {
                    const int expected = int(std::lround(g + (c[ch] - g) * 0.4));
                    QVERIFY(std::abs(channel(blended.pixel(x, y), ch) - expected) <= 1);
                }
                ++checked;
            }
        }
        QVERIFY(checked > 20);
    }

    // Nudged by hand: a drag of 12 pixels to the right moves the overlay's content with
    // it, and the nudge is kept as the pair's transform (in the study store).
    void verifyNudges(ViewportWorkspace& workspace, FusionPanel& panel, ViewportFusion& fusion,
                      SliceView& sliceView) {
        SliceView* view = &sliceView;
        Viewport* left = workspace.grid()->viewports()[0];
        panel.opacitySlider()->setValue(100);
        panel.nudgeSwitch()->setChecked(true);
        QVERIFY(fusion.nudging());
        const glm::dvec3 crosshair = left->session()->cursor()->point();
        const double x0 = 180.0, y0 = 200.0;
        std::vector<double> before;
        for (int dx = 0; dx < 60; dx += 6) {
            before.push_back(view->overlayValueAt(QPointF(x0 + dx, y0)));
        }
        QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, QPoint(300, 300));
        QTest::mouseMove(view, QPoint(306, 300));
        QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, QPoint(312, 300));
        QCOMPARE(left->session()->cursor()->point(), crosshair); // not a crosshair drag
        const glm::dmat4 expected =
            nudgedTransform(move_, view->plane().u * (12.0 * view->plane().pixelSize));
        const auto kept = workspace.links()->transform(ct_->seriesUid, moved_->seriesUid);
        QVERIFY(kept.has_value());
        for (int c = 0; c < 4; ++c) {
            QVERIFY(glm::length((*kept)[c] - expected[c]) < 1e-9);
        }
        for (int i = 0; i < int(before.size()); ++i) {
            const double now = view->overlayValueAt(QPointF(x0 + 6 * i + 12, y0));
            QVERIFY(std::isnan(before[i]) || std::abs(now - before[i]) < 1e-2);
        }
        {
            const StudyStore store(store_.path().toStdString());
            const auto stored = store.seriesTransform(ct_->seriesUid, moved_->seriesUid);
            QVERIFY(stored.has_value());
            QVERIFY(glm::length((*stored)[3] - expected[3]) < 1e-6);
        }
        // An arrow key moves it 1 mm more along the plane's v (down).
        QTest::keyClick(view, Qt::Key_Down);
        const glm::dmat4 down = nudgedTransform(expected, view->plane().v);
        QVERIFY(glm::length((*workspace.links()->transform(ct_->seriesUid, moved_->seriesUid))[3] -
                            down[3]) < 1e-9);
        panel.nudgeSwitch()->setChecked(false);
    }

    // A 3D view of the series draws the overlay as a second volume, resampled onto the
    // base's grid through the kept transform on a worker thread.
    void verifyOverlayIn3d(ViewportWorkspace& workspace, ViewportFusion& fusion, Viewport& left) {
        QSignalSpy shown3d(&fusion, &ViewportFusion::overlayShownIn3d);
        left.show(left.session(), ViewportView::Volume3D);
        QVERIFY(left.volumeView() != nullptr);
        QVERIFY(shown3d.wait(60000));
        const std::shared_ptr<const Volume>& onGrid = left.volumeView()->overlay();
        QVERIFY(onGrid != nullptr);
        QCOMPARE(onGrid->dims(), ct_->dims());
        QCOMPARE(left.volumeView()->description().overlay.volume, onGrid.get());
        const glm::dmat4 keptNow = *workspace.links()->transform(ct_->seriesUid, moved_->seriesUid);
        const glm::ivec3 voxel(256, 240, 14);
        const glm::dvec3 at(keptNow *
                            glm::dvec4(ct_->geometry().toPatient(glm::dvec3(voxel)), 1.0));
        const double expected3d = sampleAt(*moved_, moved_->geometry().toIndex(at));
        QVERIFY(std::abs(onGrid->value(voxel.x, voxel.y, voxel.z) - expected3d) < 1e-2);
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        ct_ = std::make_shared<Volume>(loadPath(test::kRealData / kCt));
        glm::dmat4 r = glm::rotate(glm::dmat4(1.0), glm::radians(6.0), glm::dvec3(0, 0, 1));
        const glm::dvec3 c = volumeCentre(ct_->geometry());
        move_ = glm::translate(glm::dmat4(1.0), c + glm::dvec3(9.0, -14.0, 5.0)) * r *
                glm::translate(glm::dmat4(1.0), -c);
        moved_ = movedCopy(*ct_, move_);
    }

    void fusesThroughTheRegistration() {
        REQUIRE_DATA(kCt);
        ViewportWorkspace workspace;
        workspace.links()->setStoreFolder(store_.path());
        workspace.resize(900, 500);
        workspace.grid()->setShape(*gridShape(QStringLiteral("1x2")));
        workspace.show();
        ViewportFusion fusion(&workspace);
        FusionPanel panel(&workspace, &fusion);
        Viewport* left = workspace.grid()->viewports()[0];
        Viewport* right = workspace.grid()->viewports()[1];
        workspace.grid()->setActiveViewport(right);
        workspace.showVolume(moved_, QStringLiteral("moved"), QString());
        workspace.grid()->setActiveViewport(left);
        workspace.showVolume(ct_, QStringLiteral("ct"), QString());
        QVERIFY(QTest::qWaitForWindowExposed(&workspace));
        SeriesSession* overlay = right->session();
        QVERIFY(overlay != nullptr && left->session() != nullptr);
        SliceView* view = left->sliceView();
        QVERIFY(view != nullptr);

        // Another Frame of Reference and nothing known: refused, saying what to do.
        QString why;
        QVERIFY(!fusion.fuse(left, overlay, &why));
        QVERIFY2(why.contains(QStringLiteral("Register")), qPrintable(why));
        QVERIFY(!view->fusion().active());
        // The panel lists the copy (not the viewport's own series) and says the same.
        QCOMPARE(panel.overlayChoice()->count(), 2);
        panel.overlayChoice()->setCurrentIndex(1);
        emit panel.overlayChoice()->activated(1);
        QVERIFY(panel.lastMessage().contains(QStringLiteral("Register")));

        workspace.links()->setTransform(ct_->seriesUid, moved_->seriesUid, move_);
        QVERIFY2(fusion.fuse(left, overlay, &why), qPrintable(why));
        QVERIFY(view->fusion().active());
        // The same modality: a grey checkerboard in the base's window, which shows the series
        // itself (float rounding may move a value by one grey level).
        QCOMPARE(fusion.styleOf(left)->mode, FusionMode::Checkerboard);
        const QImage grey = view->image().convertToFormat(QImage::Format_RGB32);
        const QImage checker = view->fusedImage();
        QCOMPARE(checker.size(), grey.size());
        int worst = 0;
        for (int y = 0; y < grey.height(); ++y) {
            for (int x = 0; x < grey.width(); ++x) {
                worst =
                    std::max(worst, std::abs(qRed(grey.pixel(x, y)) - qRed(checker.pixel(x, y))));
            }
        }
        QVERIFY2(worst <= 1, qPrintable(QString::number(worst)));

        // Hot iron blended at 40 % through the panel: each pixel is the map of the overlay's
        // value there (sampled by hand through the transform) over the grey.
        panel.refresh();
        panel.modeChoice()->setCurrentIndex(panel.modeChoice()->findData(int(FusionMode::Blend)));
        panel.colourMapChoice()->setCurrentIndex(
            panel.colourMapChoice()->findData(int(FusionColourMap::HotIron)));
        panel.opacitySlider()->setValue(40);
        const FusionStyle style = *fusion.styleOf(left);
        QCOMPARE(style.colourMap, FusionColourMap::HotIron);
        QCOMPARE(style.opacity, 0.4);
        verifyBlendedPixels(*view, grey, style);
        if (QTest::currentTestFailed()) {
            return;
        }
        // Alt+right-drag sets the overlay's window, not the base's: 40 pixels right widens it
        // by a tenth, 20 down raises the level by a twentieth of the width.
        const double baseCenter = left->session()->cursor()->windowCenter();
        QTest::mousePress(view, Qt::RightButton, Qt::AltModifier, QPoint(100, 100));
        QTest::mouseMove(view, QPoint(120, 110));
        QTest::mouseRelease(view, Qt::RightButton, Qt::AltModifier, QPoint(140, 120));
        const FusionStyle dragged = *fusion.styleOf(left);
        QVERIFY(std::abs(dragged.width - style.width * 1.1) < 1e-9);
        QVERIFY(std::abs(dragged.center - (style.center + style.width / 20.0)) < 1e-9);
        QCOMPARE(left->session()->cursor()->windowCenter(), baseCenter);
        QCOMPARE(panel.windowWidth()->value(), dragged.width);

        // Opacity 0 shows the base alone.
        panel.opacitySlider()->setValue(0);
        QVERIFY(view->fusedImage() == grey);

        verifyNudges(workspace, panel, fusion, *view);
        if (QTest::currentTestFailed()) {
            return;
        }

        // The viewport turns to coronal: the overlay stays.
        left->show(left->session(), ViewportView::Coronal);
        QVERIFY(left->sliceView()->fusion().active());
        verifyOverlayIn3d(workspace, fusion, *left);
        if (QTest::currentTestFailed()) {
            return;
        }
        // Isosurfaces draw the base alone.
        left->volumeView()->setMode(RenderMode::Isosurface);
        QVERIFY(left->volumeView()->description().overlay.volume == nullptr);
        left->show(left->session(), ViewportView::Axial);

        // None in the panel clears it.
        panel.refresh();
        panel.overlayChoice()->setCurrentIndex(0);
        emit panel.overlayChoice()->activated(0);
        QVERIFY(!left->sliceView()->fusion().active());
        QVERIFY(!fusion.styleOf(left).has_value());
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestViewportFusion test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_viewport_fusion.moc"
