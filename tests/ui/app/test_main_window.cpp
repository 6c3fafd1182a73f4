// The workstation window: layouts switched by shortcut and by double-click,
// screenshots, settings that persist, and a failed open that leaves the window
// usable. Offscreen Qt platform (the 3D view renders on the CPU there).
#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QFile>
#include <QMessageBox>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QTreeWidget>

#include <cmath>
#include <memory>

#include "core/formats/MetaImage.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/app/MainWindow.h"
#include "ui/app/ViewLayout.h"
#include "ui/mpr/SliceView.h"
#include "ui/study/StudyBrowser.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;

namespace {

// A bright ball (1000) in air (-1000) with a soft edge: slices show a disc, the
// 3D view a shaded ball.
std::shared_ptr<Volume> makeBall() {
    VolumeGeometry g;
    g.dims = {48, 48, 40};
    g.spacing = {1.0, 1.0, 1.2};
    g.origin = {-24.0, -24.0, 0.0};
    auto volume = std::make_shared<Volume>(g, VoxelType::Int16);
    auto voxels = volume->voxels<std::int16_t>();
    const glm::dvec3 centre = g.toPatient(glm::dvec3(g.dims - 1) / 2.0);
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const double r = glm::length(g.toPatient(glm::dvec3(i, j, k)) - centre);
                const double inside = std::clamp((16.0 - r) / 3.0, 0.0, 1.0);
                voxels[volume->linearIndex(i, j, k)] =
                    static_cast<std::int16_t>(std::lround(-1000.0 + 2000.0 * inside));
            }
        }
    }
    volume->modality = "CT";
    volume->description = "ball";
    return volume;
}

// Fraction of pixels brighter than mid-grey.
double brightFraction(const QImage& image) {
    const QImage grey = image.convertToFormat(QImage::Format_Grayscale8);
    qint64 bright = 0;
    for (int y = 0; y < grey.height(); ++y) {
        const uchar* row = grey.constScanLine(y);
        for (int x = 0; x < grey.width(); ++x) {
            bright += row[x] > 128 ? 1 : 0;
        }
    }
    return static_cast<double>(bright) / (static_cast<double>(grey.width()) * grey.height());
}

QMessageBox* visibleMessageBox() {
    for (QWidget* w : QApplication::topLevelWidgets()) {
        if (auto* box = qobject_cast<QMessageBox*>(w); box != nullptr && box->isVisible()) {
            return box;
        }
    }
    return nullptr;
}

} // namespace

class TestMainWindow : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void init();
    void cleanup();
    void shortcutsSwitchLayout();
    void doubleClickMaximizesAndRestores();
    void screenshotOfViewAndLayout();
    void settingsRoundTrip();
    void nothingLoadableShowsErrorAndWindowStaysUsable();
    void studyBrowserListsOpenedSeries();

private:
    void makeWindow();
    QWidget* view(int n) const { return window_->viewLayout()->views()[n]; }
    // "1" for each view shown, "0" for each hidden: axial, coronal, sagittal, 3D.
    QString visibility() const;
    void press(int keyDigit) { QTest::keyClick(window_.get(), keyDigit, Qt::ControlModifier); }

    QTemporaryDir settingsDir_;
    QTemporaryDir dataDir_;
    QString ballFile_;
    std::shared_ptr<Volume> ball_ = makeBall();
    std::unique_ptr<MainWindow> window_;
};

void TestMainWindow::initTestCase() {
    QVERIFY(settingsDir_.isValid());
    QVERIFY(dataDir_.isValid());
    // Settings of a test-only application in a temporary folder, never the user's.
    QStandardPaths::setTestModeEnabled(true);
    QCoreApplication::setOrganizationName(QStringLiteral("lucent-test"));
    QCoreApplication::setApplicationName(QStringLiteral("test_main_window"));
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settingsDir_.path());
    QVERIFY(QSettings().fileName().startsWith(settingsDir_.path()));
    ballFile_ = dataDir_.filePath(QStringLiteral("ball.mhd"));
    writeMetaImage(*ball_, QFile::encodeName(ballFile_).toStdString());
}

void TestMainWindow::makeWindow() {
    window_ = std::make_unique<MainWindow>();
    window_->show();
    window_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(window_.get()));
}

void TestMainWindow::init() {
    QSettings().clear();
    makeWindow();
    window_->resize(1100, 800);
    window_->setVolume(ball_);
    QCoreApplication::processEvents();
}

void TestMainWindow::cleanup() {
    window_.reset();
}

QString TestMainWindow::visibility() const {
    QString shown;
    for (int n = 0; n < ViewLayout::kViewCount; ++n) {
        shown += view(n)->isVisible() ? QLatin1Char('1') : QLatin1Char('0');
    }
    return shown;
}

void TestMainWindow::shortcutsSwitchLayout() {
    ViewLayout* layout = window_->viewLayout();
    QCOMPARE(layout->arrangement(), ViewLayout::Arrangement::Grid2x2);
    QCOMPARE(visibility(), QStringLiteral("1111"));

    press(Qt::Key_2); // 1x3: the three MPR views in one row
    QCOMPARE(layout->arrangement(), ViewLayout::Arrangement::Row1x3);
    QCOMPARE(visibility(), QStringLiteral("1110"));
    for (int n = 1; n < 3; ++n) {
        QCOMPARE(view(n)->mapTo(layout, QPoint()).y(), view(0)->mapTo(layout, QPoint()).y());
        QVERIFY(view(n)->mapTo(layout, QPoint()).x() > view(n - 1)->mapTo(layout, QPoint()).x());
    }

    QTest::mouseClick(view(1), Qt::LeftButton); // the coronal view becomes the active one
    QCOMPARE(layout->activeView(), view(1));
    press(Qt::Key_3); // 1x1: the active view alone, filling the area
    QCOMPARE(layout->arrangement(), ViewLayout::Arrangement::Single);
    QCOMPARE(visibility(), QStringLiteral("0100"));
    QVERIFY(view(1)->width() > layout->width() - 10);
    QVERIFY(view(1)->height() > layout->height() - 10);

    press(Qt::Key_1); // back to 2x2: axial and coronal above sagittal and 3D
    QCOMPARE(layout->arrangement(), ViewLayout::Arrangement::Grid2x2);
    QCOMPARE(visibility(), QStringLiteral("1111"));
    QVERIFY(view(2)->mapTo(layout, QPoint()).y() > view(0)->mapTo(layout, QPoint()).y());
    QCOMPARE(view(3)->mapTo(layout, QPoint()).y(), view(2)->mapTo(layout, QPoint()).y());

    // The View menu's check marks follow.
    int checked = 0;
    for (QAction* action : window_->findChildren<QAction*>()) {
        if (action->isCheckable() && action->isChecked() && action->text().startsWith("&2 x 2")) {
            ++checked;
        }
    }
    QCOMPARE(checked, 1);
}

void TestMainWindow::doubleClickMaximizesAndRestores() {
    ViewLayout* layout = window_->viewLayout();
    QTest::mouseDClick(view(2), Qt::LeftButton); // sagittal alone
    QCOMPARE(layout->arrangement(), ViewLayout::Arrangement::Single);
    QCOMPARE(visibility(), QStringLiteral("0010"));
    QVERIFY(view(2)->width() > layout->width() - 10);
    QTest::mouseDClick(view(2), Qt::LeftButton); // the 2x2 it came from
    QCOMPARE(layout->arrangement(), ViewLayout::Arrangement::Grid2x2);
    QCOMPARE(visibility(), QStringLiteral("1111"));

    // The 3D view too; and from 1x3, a second double-click goes back to 1x3.
    QTest::mouseDClick(view(3), Qt::LeftButton);
    QCOMPARE(visibility(), QStringLiteral("0001"));
    QTest::mouseDClick(view(3), Qt::LeftButton);
    QCOMPARE(visibility(), QStringLiteral("1111"));
    press(Qt::Key_2);
    QTest::mouseDClick(view(0), Qt::LeftButton);
    QCOMPARE(visibility(), QStringLiteral("1000"));
    QTest::mouseDClick(view(0), Qt::LeftButton);
    QCOMPARE(layout->arrangement(), ViewLayout::Arrangement::Row1x3);
    QCOMPARE(visibility(), QStringLiteral("1110"));
}

void TestMainWindow::screenshotOfViewAndLayout() {
    QTemporaryDir out;
    ViewLayout* layout = window_->viewLayout();

    QTest::mouseClick(view(0), Qt::LeftButton); // the axial view is the active one
    const QString axialFile = out.filePath(QStringLiteral("axial.png"));
    QString error;
    QVERIFY2(window_->saveScreenshot(axialFile, MainWindow::ScreenshotScope::ActiveView, &error),
             qPrintable(error));
    const QImage axial(axialFile);
    QCOMPARE(axial.size(), view(0)->size() * view(0)->devicePixelRatio());
    // The ball's disc: bright in the middle, dark around it.
    const double axialBright = brightFraction(axial);
    QVERIFY2(axialBright > 0.05 && axialBright < 0.9, qPrintable(QString::number(axialBright)));
    QCOMPARE(axial.convertToFormat(QImage::Format_RGB32),
             view(0)->grab().toImage().convertToFormat(QImage::Format_RGB32));

    QTest::mouseClick(view(3), Qt::LeftButton); // the 3D view
    QCOMPARE(layout->activeView(), view(3));
    const QString volumeFile = out.filePath(QStringLiteral("3d.png"));
    QVERIFY2(window_->saveScreenshot(volumeFile, MainWindow::ScreenshotScope::ActiveView, &error),
             qPrintable(error));
    const QImage volume(volumeFile);
    QCOMPARE(volume.size(), view(3)->size() * view(3)->devicePixelRatio());
    const QImage grey = volume.convertToFormat(QImage::Format_Grayscale8);
    const QRect middle(grey.width() / 2 - 5, grey.height() / 2 - 5, 10, 10);
    QVERIFY2(grey.pixelColor(middle.center()).value() > 40, "no ball in the 3D screenshot");
    QCOMPARE(grey.pixelColor(grey.width() - 3, grey.height() - 3).value(), 0); // background

    const QString layoutFile = out.filePath(QStringLiteral("layout.png"));
    QVERIFY2(window_->saveScreenshot(layoutFile, MainWindow::ScreenshotScope::Layout, &error),
             qPrintable(error));
    const QImage whole(layoutFile);
    QCOMPARE(whole.size(), layout->size() * layout->devicePixelRatio());
    // Each view's part of the layout image is that view's own screenshot.
    for (int n : {0, 3}) {
        const QRect rect(view(n)->mapTo(layout, QPoint()), view(n)->size());
        const QImage part = whole.copy(rect).convertToFormat(QImage::Format_RGB32);
        const QImage own =
            QImage(n == 0 ? axialFile : volumeFile).convertToFormat(QImage::Format_RGB32);
        QCOMPARE(part.size(), own.size());
        QCOMPARE(part, own);
    }
    QVERIFY(!window_->saveScreenshot(out.filePath(QStringLiteral("no/such/dir/x.png")),
                                     MainWindow::ScreenshotScope::Layout, &error));
    QVERIFY(!error.isEmpty());
}

void TestMainWindow::settingsRoundTrip() {
    QSignalSpy finished(window_.get(), &MainWindow::loadFinished);
    window_->openPath(ballFile_);
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 20000);
    QCOMPARE(finished.at(0).at(0).toBool(), true);
    QCOMPARE(window_->lastFolder(), QFileInfo(dataDir_.path()).absoluteFilePath());

    press(Qt::Key_2);
    QTest::mouseClick(view(2), Qt::LeftButton);
    auto* volumeDock = window_->findChild<QDockWidget*>(QStringLiteral("volumeDock"));
    QVERIFY(volumeDock != nullptr);
    QVERIFY(volumeDock->isVisible());
    volumeDock->hide();
    window_->resize(820, 610);
    QCoreApplication::processEvents();
    window_->close(); // saves
    window_.reset();

    makeWindow();
    QCOMPARE(window_->viewLayout()->arrangement(), ViewLayout::Arrangement::Row1x3);
    QCOMPARE(window_->viewLayout()->activeView(), view(2));
    QCOMPARE(window_->lastFolder(), QFileInfo(dataDir_.path()).absoluteFilePath());
    volumeDock = window_->findChild<QDockWidget*>(QStringLiteral("volumeDock"));
    QVERIFY(!volumeDock->isVisible());
    QCOMPARE(window_->size(), QSize(820, 610));
    QCOMPARE(visibility(), QStringLiteral("1110"));

    // A maximized view comes back as 1x1 of that view.
    QTest::mouseDClick(view(1), Qt::LeftButton);
    window_->close();
    window_.reset();
    makeWindow();
    QCOMPARE(window_->viewLayout()->arrangement(), ViewLayout::Arrangement::Single);
    QCOMPARE(visibility(), QStringLiteral("0100"));
}

void TestMainWindow::nothingLoadableShowsErrorAndWindowStaysUsable() {
    QTemporaryDir folder;
    QFile notes(folder.filePath(QStringLiteral("notes.txt")));
    QVERIFY(notes.open(QIODevice::WriteOnly));
    notes.write("not an image\n");
    notes.close();

    QSignalSpy finished(window_.get(), &MainWindow::loadFinished);
    window_->openPath(folder.path());
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 20000);
    QCOMPARE(finished.at(0).at(0).toBool(), false);
    QMessageBox* box = nullptr;
    QTRY_VERIFY((box = visibleMessageBox()) != nullptr);
    QCOMPARE(box->icon(), QMessageBox::Critical);
    QVERIFY2(box->text().contains(folder.path()), qPrintable(box->text()));
    QVERIFY2(box->informativeText().contains(QStringLiteral("nothing loadable")),
             qPrintable(box->informativeText()));
    QVERIFY2(box->detailedText().contains(QStringLiteral("notes.txt")),
             qPrintable(box->detailedText()));
    // The volume shown before is still there.
    QVERIFY(window_->volume() == ball_);

    box->button(QMessageBox::Ok)->click();
    QTRY_VERIFY(visibleMessageBox() == nullptr);

    // Usable: shortcuts work and the next open succeeds.
    // (The offscreen platform has no window manager to hand activation back.)
    window_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(window_.get()));
    press(Qt::Key_2);
    QCOMPARE(window_->viewLayout()->arrangement(), ViewLayout::Arrangement::Row1x3);
    window_->openPath(ballFile_);
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 2, 20000);
    QCOMPARE(finished.at(1).at(0).toBool(), true);
    QVERIFY(window_->volume() != ball_);
    QCOMPARE(window_->volume()->dims(), ball_->dims());
    QVERIFY(visibleMessageBox() == nullptr);
}

void TestMainWindow::studyBrowserListsOpenedSeries() {
    auto* studies = window_->findChild<StudyBrowser*>();
    QVERIFY(studies != nullptr);
    QCOMPARE(studies->count(), 0); // setVolume alone is no opened series

    // A second series: the ball's left half only (other dimensions).
    VolumeGeometry halfGeometry = ball_->geometry();
    halfGeometry.dims.x = 24;
    Volume half(halfGeometry, VoxelType::Int16);
    auto voxels = half.voxels<std::int16_t>();
    for (int k = 0; k < halfGeometry.dims.z; ++k) {
        for (int j = 0; j < halfGeometry.dims.y; ++j) {
            for (int i = 0; i < halfGeometry.dims.x; ++i) {
                voxels[half.linearIndex(i, j, k)] =
                    static_cast<std::int16_t>(ball_->value(i, j, k));
            }
        }
    }
    half.modality = "CT";
    half.description = "half";
    const QString halfFile = dataDir_.filePath(QStringLiteral("half.mhd"));
    writeMetaImage(half, QFile::encodeName(halfFile).toStdString());

    QSignalSpy finished(window_.get(), &MainWindow::loadFinished);
    window_->openPath(ballFile_);
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 20000);
    const QString ballUid = QString::fromStdString(window_->volume()->seriesUid);
    window_->openPath(halfFile);
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 2, 20000);
    const QString halfUid = QString::fromStdString(window_->volume()->seriesUid);
    QTRY_COMPARE_WITH_TIMEOUT(studies->pending(), 0, 20000); // the folder scans
    QCOMPARE(studies->count(), 2);
    QTreeWidgetItem* halfItem = studies->findSeries(halfFile, halfUid);
    QTreeWidgetItem* ballItem = studies->findSeries(ballFile_, ballUid);
    QVERIFY(halfItem != nullptr && ballItem != nullptr);
    QVERIFY2(halfItem->text(0).contains(QStringLiteral("24 x 48 x 40")),
             qPrintable(halfItem->text(0)));
    QVERIFY2(ballItem->text(0).contains(QStringLiteral("ball")), qPrintable(ballItem->text(0)));
    QVERIFY(ballItem->text(0).contains(QStringLiteral("48 x 48 x 40")));
    QVERIFY(ballItem->font(0).bold()); // opened in this session
    // No patient in a MetaImage: both under one "Unknown patient", a study each.
    QCOMPARE(studies->tree()->topLevelItemCount(), 1);
    QCOMPARE(studies->tree()->topLevelItem(0)->text(0), QStringLiteral("Unknown patient"));
    QCOMPARE(studies->tree()->topLevelItem(0)->childCount(), 2);

    // The thumbnail: the ball's middle slice, a bright disc on black.
    const QImage thumb = StudyBrowser::thumbnail(*ball_);
    QCOMPARE(thumb.size(), QSize(StudyBrowser::kThumbnailSize, StudyBrowser::kThumbnailSize));
    QVERIFY(thumb.pixelColor(thumb.width() / 2, thumb.height() / 2).value() > 200);
    QCOMPARE(thumb.pixelColor(2, 2).value(), 0);
    QVERIFY(!ballItem->icon(0).isNull());

    // A click on the ball opens it again.
    auto* dock = window_->findChild<QDockWidget*>(QStringLiteral("studyDock"));
    QVERIFY(dock != nullptr && dock->isVisible());
    QTreeWidget* tree = studies->tree();
    tree->scrollToItem(ballItem);
    QTest::mouseClick(tree->viewport(), Qt::LeftButton, {},
                      tree->visualItemRect(ballItem).center());
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 3, 20000);
    QCOMPARE(finished.at(2).at(0).toBool(), true);
    QCOMPARE(window_->volume()->dims(), ball_->dims());
    QCOMPARE(studies->count(), 2);
}

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestMainWindow test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_main_window.moc"
