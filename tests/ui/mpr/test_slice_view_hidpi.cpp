// The MPR view on a screen of device pixel ratio 2 (QT_SCALE_FACTOR=2 on the
// offscreen platform): the slice is sampled at device pixels and drawn at the
// widget's logical size, while clicks, the crosshair and measurements stay in
// logical (widget) coordinates. A baseline of the demo CT's axial view at ratio 2.
#include <QApplication>
#include <QTest>

#include <cmath>
#include <filesystem>
#include <memory>

#include "core/formats/InVesaliusProject.h"
#include "tests/support/BaselineImage.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SeriesMeasurements.h"
#include "ui/mpr/SliceView.h"

using namespace lucent;

namespace {

const std::filesystem::path kDemoCt = "/usr/share/doc/invesalius-examples/examples/Cranium.inv3";
constexpr int kLogicalSize = 100;

// Stripes two voxels wide along x (0 and 1000), 1 mm voxels, 200 mm across: fitted
// to 100 logical pixels, a logical pixel is 2 mm and a device pixel 1 mm, so only
// device-pixel sampling shows neighbouring device columns that differ.
std::shared_ptr<const Volume> makeStripes() {
    VolumeGeometry g;
    g.dims = {200, 200, 3};
    g.spacing = {1.0, 1.0, 1.0};
    auto volume = std::make_shared<Volume>(g, VoxelType::Float32);
    auto voxels = volume->voxels<float>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                voxels[volume->linearIndex(i, j, k)] = (i / 2) % 2 == 0 ? 0.0f : 1000.0f;
            }
        }
    }
    return volume;
}

} // namespace

class TestSliceViewHiDpi : public QObject {
    Q_OBJECT
    std::shared_ptr<const Volume> stripes_ = makeStripes();
    std::unique_ptr<MprCursor> cursor_;
    std::unique_ptr<SliceView> view_;
    std::unique_ptr<SeriesMeasurements> measurements_;

    void showView(const std::shared_ptr<const Volume>& volume, int size) {
        cursor_ = std::make_unique<MprCursor>();
        cursor_->setPoint(volume->geometry().toPatient(glm::dvec3(volume->dims() / 2)));
        view_ = std::make_unique<SliceView>(Orientation::Axial, cursor_.get());
        view_->resize(size, size);
        view_->setVolume(volume);
        measurements_ = std::make_unique<SeriesMeasurements>(volume);
        view_->setMeasurements(measurements_.get());
        view_->show();
        QVERIFY(QTest::qWaitForWindowExposed(view_.get()));
    }

private slots:
    void init() {
        showView(stripes_, kLogicalSize);
        cursor_->setWindow(500.0, 1000.0);
    }
    void cleanup() {
        view_.reset();
        cursor_.reset();
    }

    void screenHasRatioTwo() {
        QCOMPARE(view_->devicePixelRatioF(), 2.0);
        QCOMPARE(view_->size(), QSize(kLogicalSize, kLogicalSize));
    }

    void imageHasDevicePixels() {
        const QImage image = view_->image();
        QCOMPARE(image.size(), QSize(2 * kLogicalSize, 2 * kLogicalSize));
        QCOMPARE(image.devicePixelRatio(), 2.0);
        // The plane the mouse and overlays use stays logical.
        QCOMPARE(view_->plane().width, kLogicalSize);
        QCOMPARE(view_->plane().height, kLogicalSize);
    }

    void deviceColumnsShowDetailOfTheirOwn() {
        // Each device pixel takes the value at its own logical position: (i / 2, y).
        const SlicePlane logical = view_->plane();
        const VolumeGeometry& g = stripes_->geometry();
        for (int i = 0; i < 2 * kLogicalSize; ++i) {
            const QPointF pos(i / 2.0, 50.0);
            const double expected =
                sampleAt(*stripes_, g.toIndex(logical.pointAt(pos.x(), pos.y())));
            QVERIFY2(std::abs(view_->valueAt(pos) - expected) < 1e-3,
                     qPrintable(QString("device column %1: %2, expected %3")
                                    .arg(i)
                                    .arg(view_->valueAt(pos))
                                    .arg(expected)));
        }
        // On screen: a logical image scaled up would repeat every column twice.
        const QImage shown = view_->grab().toImage().convertToFormat(QImage::Format_RGB32);
        QCOMPARE(shown.size(), QSize(2 * kLogicalSize, 2 * kLogicalSize));
        const int row = kLogicalSize; // the middle, clear of the overlay texts
        int pairsThatDiffer = 0;
        for (int x = 20; x + 1 < 2 * kLogicalSize - 20; x += 2) {
            const int a = qGray(shown.pixel(x, row + 7)), b = qGray(shown.pixel(x + 1, row + 7));
            pairsThatDiffer += std::abs(a - b) > 60;
        }
        QVERIFY2(pairsThatDiffer > 30, qPrintable(QString::number(pairsThatDiffer)));
    }

    void clicksAndMeasurementsStayLogical() {
        QTest::mouseClick(view_.get(), Qt::LeftButton, {}, QPoint(30, 40));
        const glm::dvec3 clicked = view_->plane().pointAt(30.0, 40.0);
        QVERIFY(glm::distance(cursor_->point(), clicked) < 1e-9);
        // 2 mm per logical pixel: 60 logical pixels are 120 mm.
        QTest::keyClick(view_.get(), Qt::Key_D);
        QTest::mousePress(view_.get(), Qt::LeftButton, {}, QPoint(20, 60));
        QTest::mouseMove(view_.get(), QPoint(50, 60));
        QTest::mouseRelease(view_.get(), Qt::LeftButton, {}, QPoint(80, 60));
        QCOMPARE(measurements_->measurements().size(), std::size_t(1));
        const double length = measurementLengthMm(measurements_->measurements()[0]);
        QVERIFY2(std::abs(length - 60.0 * view_->plane().pixelSize) < 1e-6,
                 qPrintable(QString::number(length)));
        QVERIFY(std::abs(view_->plane().pixelSize - 2.0) < 1e-9);
    }

    void demoCtMatchesTheBaseline() {
        if (!std::filesystem::exists(kDemoCt)) {
            QSKIP("the demo CT (Debian package invesalius-examples) is not installed");
        }
        auto ct = std::make_shared<Volume>(readInVesalius(kDemoCt));
        showView(ct, 256);
        cursor_->setWindow(40.0, 400.0);
        const QImage shown = view_->grab().toImage();
        QCOMPARE(shown.size(), QSize(512, 512));
        LUCENT_COMPARE_BASELINE(shown, QStringLiteral("mpr_axial_demo_ct_dpr2"), 30.0, 0.95);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    // Before the application: every screen has a device pixel ratio of 2.
    qputenv("QT_SCALE_FACTOR", "2");
    QApplication app(argc, argv);
    TestSliceViewHiDpi test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_slice_view_hidpi.moc"
