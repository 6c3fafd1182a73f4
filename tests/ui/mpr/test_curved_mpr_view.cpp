// Curved MPR driven as a reader would, on the real Philips CT head phantom: P
// on the axial view, five clicks along an arc in front of the head, Enter;
// the path reaches the curved MPR window, whose stretched reformation (a
// panoramic of the skull, as a dental reformat looks) is compared with a
// baseline under an explicit bound. Moving along the reformation moves the
// cross-section and the MPR crosshair. LUCENT_UPDATE_BASELINES=1 writes the
// baseline (look at it before committing it); on failure the actual image is
// saved beside the binaries. Label ui; offscreen Qt platform.
#include <QApplication>
#include <QComboBox>
#include <QSignalSpy>
#include <QTest>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "core/io/Catalog.h"
#include "tests/support/BaselineImage.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/mpr/CurvedMprView.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SliceView.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

const fs::path kSeries = fs::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2010";
constexpr double kMinPsnr = 40.0; // dB: the same arithmetic, only rounding may differ
constexpr double kMinSsim = 0.99;

} // namespace

class TestCurvedMprView : public QObject {
    Q_OBJECT
    std::shared_ptr<const Volume> volume_;
    std::unique_ptr<MprCursor> cursor_;
    std::unique_ptr<SliceView> axial_;
    std::vector<glm::dvec3> path_;
    glm::dvec3 up_{0.0};

private slots:
    void initTestCase() {
        if (!fs::exists(kSeries)) {
            QSKIP(qPrintable("real test data not found: " +
                             QString::fromStdString(kSeries.string())));
        }
        volume_ = std::make_shared<const Volume>(loadPath(kSeries));
        cursor_ = std::make_unique<MprCursor>();
        cursor_->setPoint(volume_->geometry().toPatient(glm::dvec3(volume_->dims() / 2)));
        cursor_->setWindow(300.0, 1500.0); // bone
        axial_ = std::make_unique<SliceView>(Orientation::Axial, cursor_.get());
        axial_->resize(400, 400);
        axial_->setVolume(volume_);
        axial_->show();
        QVERIFY(QTest::qWaitForWindowExposed(axial_.get()));
    }
    void cleanupTestCase() {
        axial_.reset();
        cursor_.reset();
    }

    void clicksOnAnMprViewMakeAPath() {
        QSignalSpy drawn(axial_.get(), &SliceView::curvedPathDrawn);
        QTest::keyClick(axial_.get(), Qt::Key_P);
        QCOMPARE(axial_->tool(), SliceView::Tool::CurvedPath);
        // An arc in front of the head (anterior is up in an axial view).
        for (int k = 0; k < 5; ++k) {
            const double a = std::numbers::pi * (200.0 + 35.0 * k) / 180.0;
            QTest::mouseClick(axial_.get(), Qt::LeftButton, {},
                              QPoint(200 + int(120 * std::cos(a)), 200 + int(120 * std::sin(a))));
        }
        QCOMPARE(axial_->pathPoints().size(), std::size_t(5));
        QTest::keyClick(axial_.get(), Qt::Key_Return);
        QCOMPARE(drawn.size(), 1);
        QCOMPARE(axial_->tool(), SliceView::Tool::Crosshair);
        QVERIFY(axial_->pathPoints().empty());
        path_ = drawn[0][0].value<std::vector<glm::dvec3>>();
        up_ = drawn[0][1].value<glm::dvec3>();
        QCOMPARE(path_.size(), std::size_t(5));
        const SlicePlane plane = axial_->plane();
        for (const glm::dvec3& p : path_) {
            QVERIFY(std::abs(plane.distance(p)) < 1e-9); // on the plane it was drawn on
        }
        QVERIFY(glm::distance(up_, plane.normal()) < 1e-12);
        // Escape drops a path half drawn.
        QTest::keyClick(axial_.get(), Qt::Key_P);
        QTest::mouseClick(axial_.get(), Qt::LeftButton, {}, QPoint(100, 100));
        QTest::keyClick(axial_.get(), Qt::Key_Escape);
        QVERIFY(axial_->pathPoints().empty());
        QCOMPARE(drawn.size(), 1);
    }

    void stretchedReformationMatchesTheBaseline() {
        QVERIFY(!path_.empty());
        CurvedMprView view(cursor_.get());
        view.resize(900, 640);
        view.setPath(volume_, path_, up_);
        view.setKind(CurvedMprView::Kind::Stretched);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        const QImage actual = view.reformationImage();
        // Rows at true length along the path, one per pixel of the finest spacing.
        const double pixel = view.reformation().pixelSize;
        QCOMPARE(actual.height(), int(std::floor(view.centerline().length() / pixel)) + 1);
        const test::BaselineResult r =
            test::compareWithBaseline(actual, "curved_mpr_philips_s2010", kMinPsnr, kMinSsim);
        if (r.written) {
            QSKIP("baseline written: curved_mpr_philips_s2010");
        }
        QVERIFY2(r.failure.isEmpty(), qPrintable("curved MPR: " + r.failure));
    }

    void movingAlongThePathMovesCrossSectionAndCrosshair() {
        CurvedMprView view(cursor_.get());
        view.resize(900, 640);
        view.setPath(volume_, path_, up_);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        QCOMPARE(view.kindBox()->currentIndex(), 0); // straightened first
        const QImage before = view.crossSectionImage();
        // The reformation pane is the window's first child pane: move over its upper part.
        QWidget* pane = view.childAt(QPoint(100, 100));
        QVERIFY(pane != nullptr);
        QTest::mouseMove(pane, QPoint(pane->width() / 2, pane->height() / 4));
        QTest::mouseClick(pane, Qt::LeftButton, {}, QPoint(pane->width() / 2, pane->height() / 4));
        QVERIFY(view.arc() < 0.45 * view.centerline().length());
        QVERIFY(glm::distance(cursor_->point(), view.centerline().pointAt(view.arc())) < 1e-9);
        QVERIFY(view.crossSectionImage() != before);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestCurvedMprView test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_curved_mpr_view.moc"
