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

#include "tests/support/BaselineImage.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/app/MainWindow.h"
#include "ui/study/StudyBrowser.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;

namespace {

const std::filesystem::path kStudy =
    std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2010";
constexpr double kMinPsnr = 30.0; // dB
constexpr double kMinSsim = 0.95;

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

        const test::BaselineResult r =
            test::compareWithBaseline(actual, "main_window_philips_s2010", kMinPsnr, kMinSsim);
        if (r.written) {
            QSKIP("baseline written: main_window_philips_s2010");
        }
        QVERIFY2(r.failure.isEmpty(), qPrintable("main window: " + r.failure));
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestMainWindowBaseline test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_main_window_baseline.moc"
