// File > Export Movie on a real CT: a turntable of the 3D view decodes with the
// asked frames and size, frame k being the view's scene turned k * DEG / N (CPU
// reference, 35 dB); a cancelled cine and an unwritable output leave no file;
// without a volume there is nothing to export. Offscreen; the export renders on
// its own thread (GL through EGL where it can, else the CPU).
#include <QApplication>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QSpinBox>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>

#include <memory>

#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/movie/MovieFrames.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/support/MovieProbe.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/RealData.h"
#include "ui/app/MainWindow.h"
#include "ui/app/MovieExportDialog.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;

namespace {

const char* kCt = "dcm_qa_ct/Philips_S21570/S2010"; // 28 slices 512x512, 5 mm

} // namespace

class TestMovieExport : public QObject {
    Q_OBJECT
    QTemporaryDir settingsDir_;
    std::unique_ptr<MainWindow> window_;

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QCoreApplication::setOrganizationName(QStringLiteral("lucent-test"));
        QCoreApplication::setApplicationName(QStringLiteral("test_movie_export"));
        QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settingsDir_.path());
        window_ = std::make_unique<MainWindow>();
        window_->show();
        QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
    }

    void nothingToExportWithoutAVolume() { QVERIFY(window_->openMovieExport() == nullptr); }

    void turntableOfTheView() {
        REQUIRE_DATA(kCt);
        QVERIFY2(!test::ffmpegTool("ffprobe").isEmpty(),
                 "ffprobe is needed (apt-get install ffmpeg)");
        window_->setVolume(std::make_shared<const Volume>(loadPath(test::kRealData / kCt)));
        QTemporaryDir out;
        MovieExportDialog* dialog = window_->openMovieExport();
        QVERIFY(dialog != nullptr);
        QCOMPARE(dialog->kind()->currentIndex(), 0);
        dialog->frames()->setValue(6);
        dialog->degrees()->setValue(180.0);
        dialog->movieWidth()->setValue(64);
        dialog->movieHeight()->setValue(48);
        dialog->output()->setText(out.filePath("turn.webm"));
        QSignalSpy finished(dialog, &MovieExportDialog::exportFinished);
        QTest::mouseClick(dialog->exportButton(), Qt::LeftButton);
        QVERIFY(dialog->running());
        QVERIFY(finished.wait(120000));
        QVERIFY2(finished.at(0).at(0).toBool(), qPrintable(finished.at(0).at(1).toString()));
        QCOMPARE(test::filesIn(out.path()), QStringList{"turn.webm"});

        const test::ProbedMovie probed = test::probeMovie(out.filePath("turn.webm"));
        QVERIFY2(probed.error.isEmpty(), qPrintable(probed.error));
        QCOMPARE(probed.codec, QString("vp9"));
        QCOMPARE(probed.frames, 6);
        QCOMPARE(probed.width, 64);
        QCOMPARE(probed.height, 48);
        const QString frames = out.filePath("frames");
        const QString decodeError = test::decodeFrames(out.filePath("turn.webm"), frames);
        QVERIFY2(decodeError.isEmpty(), qPrintable(decodeError));
        // Frame 4: the 3D view's scene turned 4 * 180 / 6 = 120 degrees.
        CpuRayCaster cpu(*window_->volume());
        const RenderDescription expected =
            turntableFrame(window_->volumeView()->description(64, 48), 180.0, 6, 4);
        const double db =
            psnr(cpu.render(expected).image, readPng(test::framePng(frames, 4).toStdString()));
        qInfo("frame 4 against the CPU render of the view turned 120 degrees: %.2f dB", db);
        QVERIFY2(db >= 35.0, qPrintable(QString::number(db)));
        dialog->close();
    }

    void cancelledCineLeavesNoFile() {
        REQUIRE_DATA(kCt);
        QVERIFY(window_->volume());
        QTemporaryDir out;
        MovieExportDialog* dialog = window_->openMovieExport();
        dialog->kind()->setCurrentIndex(1);
        QVERIFY(!dialog->degrees()->isEnabled());
        QCOMPARE(dialog->frames()->value(), 0); // every slice: 512 along j
        dialog->axis()->setCurrentIndex(1);
        dialog->movieWidth()->setValue(256);
        dialog->movieHeight()->setValue(256);
        dialog->output()->setText(out.filePath("cine.mp4"));
        QSignalSpy finished(dialog, &MovieExportDialog::exportFinished);
        int total = 0;
        connect(dialog, &MovieExportDialog::progressed, dialog,
                [dialog, &total](int done, int all) {
                    total = all;
                    if (done >= 1 && dialog->running()) {
                        QTest::mouseClick(dialog->closeButton(), Qt::LeftButton); // Cancel
                    }
                });
        QTest::mouseClick(dialog->exportButton(), Qt::LeftButton);
        QVERIFY(finished.wait(120000));
        QCOMPARE(total, 512);
        QCOMPARE(finished.at(0).at(0).toBool(), false);
        QVERIFY2(dialog->status()->text().contains("Cancelled"),
                 qPrintable(dialog->status()->text()));
        QCOMPARE(test::filesIn(out.path()), QStringList{});
        dialog->close();
    }

    void unwritableOutputIsRefusedBeforeRendering() {
        REQUIRE_DATA(kCt);
        QTemporaryDir out;
        QFile blocker(out.filePath("blocker"));
        QVERIFY(blocker.open(QIODevice::WriteOnly));
        blocker.close();
        MovieExportDialog* dialog = window_->openMovieExport();
        dialog->movieWidth()->setValue(64);
        dialog->movieHeight()->setValue(64);
        dialog->output()->setText(out.filePath("blocker/turn.mp4"));
        QTest::mouseClick(dialog->exportButton(), Qt::LeftButton);
        QVERIFY(!dialog->running());
        QVERIFY2(dialog->status()->text().contains("cannot write a file in"),
                 qPrintable(dialog->status()->text()));
        dialog->output()->setText(out.filePath("turn.mkv"));
        QTest::mouseClick(dialog->exportButton(), Qt::LeftButton);
        QVERIFY(!dialog->running());
        QVERIFY2(dialog->status()->text().contains("unknown movie format"),
                 qPrintable(dialog->status()->text()));
        QCOMPARE(test::filesIn(out.path()), QStringList{"blocker"});
        dialog->close();
    }

    void cleanupTestCase() { window_.reset(); }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestMovieExport test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_movie_export.moc"
