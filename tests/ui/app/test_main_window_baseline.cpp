// The whole workstation window on a known study (the real Philips CT, 5 mm),
// compared with a baseline screenshot under an explicit bound. Offscreen Qt
// platform: the 3D view renders on the CPU, so the image depends on the code,
// not on a GPU. LUCENT_UPDATE_BASELINES=1 writes the baseline instead (look at
// it before committing it). On failure the actual image is saved beside the
// test binary and its path printed.
#include <QApplication>
#include <QDir>
#include <QFileInfo>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>

#include "core/image/ImageMetrics.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/app/MainWindow.h"
#include "ui/study/StudyBrowser.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;

namespace {

const std::filesystem::path kStudy =
    std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2010";
const QString kBaseline =
    QStringLiteral(LUCENT_SOURCE_DIR "/tests/ui/app/baselines/main_window_philips_s2010.png");
constexpr double kMinPsnr = 30.0; // dB
constexpr double kMinSsim = 0.95;

ImageRGBA8 toRgba(const QImage& image) {
    const QImage rgba = image.convertToFormat(QImage::Format_RGBA8888);
    ImageRGBA8 out = ImageRGBA8::filled(rgba.width(), rgba.height(), 0);
    for (int y = 0; y < rgba.height(); ++y) {
        const uchar* row = rgba.constScanLine(y);
        std::copy(row, row + std::size_t(rgba.width()) * 4,
                  out.pixels.begin() + std::ptrdiff_t(out.offset(0, y)));
    }
    return out;
}

} // namespace

class TestMainWindowBaseline : public QObject {
    Q_OBJECT
    QTemporaryDir settingsDir_;

private slots:
    void initTestCase() {
        if (!std::filesystem::exists(kStudy)) {
            QSKIP("real DICOM data (../shared/data) is absent");
        }
        QVERIFY(settingsDir_.isValid());
        // Default settings, never the user's: the layout and docks as on a first start.
        QStandardPaths::setTestModeEnabled(true);
        QCoreApplication::setOrganizationName(QStringLiteral("lucent-test"));
        QCoreApplication::setApplicationName(QStringLiteral("test_main_window_baseline"));
        QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settingsDir_.path());
        QSettings().clear();
    }

    void windowOnAKnownStudyMatchesTheBaseline() {
        MainWindow window;
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        window.resize(1280, 800);
        QSignalSpy finished(&window, &MainWindow::loadFinished);
        window.openPath(QString::fromStdString(kStudy.string()));
        QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 60000);
        QVERIFY(finished.at(0).at(0).toBool());
        auto* studies = window.findChild<StudyBrowser*>();
        QVERIFY(studies != nullptr);
        QTRY_COMPARE_WITH_TIMEOUT(studies->pending(), 0, 60000);
        auto* view = window.findChild<VolumeView*>();
        QVERIFY(view != nullptr);
        QTRY_VERIFY_WITH_TIMEOUT(!view->lastFrame().empty() && view->lastFrameCurrent(), 60000);
        // Offscreen cannot show a QOpenGLWidget, even where it could make a
        // context (DISPLAY set): the CPU renderer, and the notice says why.
        QCOMPARE(view->backend(), VolumeView::Backend::Cpu);
        if (!qEnvironmentVariableIsEmpty("DISPLAY")) {
            QVERIFY2(view->notice().contains("offscreen"), qPrintable(view->notice()));
        }

        // Settled: two grabs a moment apart are the same picture.
        QImage actual = window.grab().toImage();
        for (int tries = 0; tries < 20; ++tries) {
            QTest::qWait(200);
            const QImage again = window.grab().toImage();
            if (again == actual) {
                break;
            }
            actual = again;
        }

        if (qEnvironmentVariableIsSet("LUCENT_UPDATE_BASELINES")) {
            QDir().mkpath(QFileInfo(kBaseline).path());
            QVERIFY(actual.save(kBaseline));
            QSKIP(qPrintable("baseline written: " + kBaseline));
        }
        const QImage baseline(kBaseline);
        QVERIFY2(!baseline.isNull(), qPrintable("no baseline " + kBaseline));
        const QString saved = QStringLiteral(LUCENT_BIN_DIR "/main_window_actual.png");
        if (actual.size() != baseline.size()) {
            actual.save(saved);
            QFAIL(qPrintable(QString("window %1x%2, baseline %3x%4; actual saved as %5")
                                 .arg(actual.width())
                                 .arg(actual.height())
                                 .arg(baseline.width())
                                 .arg(baseline.height())
                                 .arg(saved)));
        }
        const ImageRGBA8 a = toRgba(actual), b = toRgba(baseline);
        const double p = psnr(a, b), s = ssim(a, b);
        qInfo("main window against the baseline: PSNR %.2f dB, SSIM %.4f", p, s);
        if (p < kMinPsnr || s < kMinSsim) {
            actual.save(saved);
            QFAIL(qPrintable(QString("PSNR %1 dB (at least %2), SSIM %3 (at least %4); actual "
                                     "saved as %5")
                                 .arg(p)
                                 .arg(kMinPsnr)
                                 .arg(s)
                                 .arg(kMinSsim)
                                 .arg(saved)));
        }
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestMainWindowBaseline test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_main_window_baseline.moc"
