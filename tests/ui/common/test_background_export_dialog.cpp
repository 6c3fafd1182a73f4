// BackgroundExportDialog, the base of the movie and DICOM export dialogs: a job
// that writes a file step by step on the worker thread (as the real exports do:
// the file stays only when whole) shows its progress, ends done, failed or
// cancelled with its message; a cancel or a failure leaves no file by the time
// exportFinished is emitted; closing the dialog mid-export cancels and waits.
// Offscreen.
#include <QApplication>
#include <QFile>
#include <QFormLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>

#include "tests/support/OffscreenPlatform.h"
#include "ui/common/BackgroundExportDialog.h"

using namespace lucent;

namespace {

// A file that is removed when it goes unless kept: what MovieWriter and
// DicomExport do with an unfinished output.
class PartialFile {
public:
    explicit PartialFile(const QString& path) : file_(path) {
        if (!file_.open(QIODevice::WriteOnly)) {
            throw std::runtime_error("cannot write " + path.toStdString());
        }
    }
    ~PartialFile() {
        file_.close();
        if (!kept_) {
            file_.remove();
        }
    }
    PartialFile(const PartialFile&) = delete;
    PartialFile& operator=(const PartialFile&) = delete;
    void write(int step) { file_.write(QByteArray::number(step) + '\n'); }
    void keep() { kept_ = true; }

private:
    QFile file_;
    bool kept_ = false;
};

// How the test job ends.
enum class Ending { Finish, Fail, WaitForCancel };

class StepDialog : public BackgroundExportDialog {
public:
    StepDialog(QString path, Ending ending, int steps)
        : BackgroundExportDialog(nullptr), path_(std::move(path)), ending_(ending), steps_(steps) {
        addExportRows(new QFormLayout(this));
    }

private:
    void start() override {
        startJob(QStringLiteral("Writing..."), [this, file = std::make_unique<PartialFile>(path_),
                                                ending = ending_,
                                                steps = steps_](std::stop_token stop) {
            for (int step = 1; step <= steps; ++step) {
                file->write(step);
                reportProgress(step, steps);
                if (ending == Ending::Fail) {
                    throw std::runtime_error("the disk is full");
                }
            }
            if (ending == Ending::WaitForCancel) {
                const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
                while (!stop.stop_requested() && std::chrono::steady_clock::now() < until) {
                    std::this_thread::sleep_for(std::chrono::milliseconds(5));
                }
                return ExportOutcome{false, QStringLiteral("Cancelled.")};
            }
            file->keep();
            return ExportOutcome{true, QStringLiteral("Wrote %1 steps").arg(steps)};
        });
    }

    QString path_;
    Ending ending_;
    int steps_;
};

} // namespace

class TestBackgroundExportDialog : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;

private slots:
    void finishedExportReportsProgressAndKeepsTheFile() {
        const QString path = dir_.filePath("done.txt");
        StepDialog dialog(path, Ending::Finish, 4);
        dialog.show();
        QSignalSpy progressed(&dialog, &BackgroundExportDialog::progressed);
        QSignalSpy finished(&dialog, &BackgroundExportDialog::exportFinished);
        QTest::mouseClick(dialog.exportButton(), Qt::LeftButton);
        QVERIFY(dialog.running());
        QVERIFY(!dialog.exportButton()->isEnabled());
        QCOMPARE(dialog.closeButton()->text(), QStringLiteral("Cancel"));
        QCOMPARE(dialog.status()->text(), QStringLiteral("Writing..."));
        QVERIFY(finished.wait(10000));
        QCOMPARE(finished[0][0].toBool(), true);
        QCOMPARE(finished[0][1].toString(), QStringLiteral("Wrote 4 steps"));
        QCOMPARE(progressed.size(), 4);
        QCOMPARE(progressed.last()[0].toInt(), 4);
        QCOMPARE(progressed.last()[1].toInt(), 4);
        QCOMPARE(dialog.progressBar()->maximum(), 4);
        QCOMPARE(dialog.progressBar()->value(), 4);
        QVERIFY(!dialog.running());
        QVERIFY(dialog.exportButton()->isEnabled());
        QCOMPARE(dialog.closeButton()->text(), QStringLiteral("Close"));
        QCOMPARE(dialog.status()->text(), QStringLiteral("Wrote 4 steps"));
        QVERIFY(QFile::exists(path));
    }

    void cancelLeavesNoFileWhenFinishedIsEmitted() {
        const QString path = dir_.filePath("cancelled.txt");
        StepDialog dialog(path, Ending::WaitForCancel, 2);
        dialog.show();
        QSignalSpy progressed(&dialog, &BackgroundExportDialog::progressed);
        bool fileAtFinish = true;
        connect(&dialog, &BackgroundExportDialog::exportFinished, this,
                [&] { fileAtFinish = QFile::exists(path); });
        QSignalSpy finished(&dialog, &BackgroundExportDialog::exportFinished);
        QTest::mouseClick(dialog.exportButton(), Qt::LeftButton);
        QTRY_COMPARE_WITH_TIMEOUT(progressed.size(), 2, 10000);
        QVERIFY(QFile::exists(path)); // half-way: the partial file is there
        QTest::mouseClick(dialog.closeButton(), Qt::LeftButton); // reads Cancel
        QCOMPARE(dialog.status()->text(), QStringLiteral("Cancelling..."));
        QVERIFY(finished.wait(10000));
        QCOMPARE(finished[0][0].toBool(), false);
        QVERIFY(!fileAtFinish);
        QVERIFY(!QFile::exists(path));
        QCOMPARE(dialog.status()->text(), QStringLiteral("Cancelled."));
        QCOMPARE(dialog.progressBar()->value(), 0);
        QVERIFY(dialog.isVisible()); // a cancel does not close the dialog
        QCOMPARE(dialog.closeButton()->text(), QStringLiteral("Close"));
        QTest::mouseClick(dialog.closeButton(), Qt::LeftButton); // now it closes
        QVERIFY(!dialog.isVisible());
        QCOMPARE(dialog.result(), int(QDialog::Rejected));
    }

    void failureSaysWhyAndLeavesNoFile() {
        const QString path = dir_.filePath("failed.txt");
        StepDialog dialog(path, Ending::Fail, 3);
        dialog.show();
        QSignalSpy finished(&dialog, &BackgroundExportDialog::exportFinished);
        QTest::mouseClick(dialog.exportButton(), Qt::LeftButton);
        QVERIFY(finished.wait(10000));
        QCOMPARE(finished[0][0].toBool(), false);
        QCOMPARE(finished[0][1].toString(), QStringLiteral("the disk is full"));
        QCOMPARE(dialog.status()->text(), QStringLiteral("the disk is full"));
        QVERIFY(!QFile::exists(path));
        QVERIFY(dialog.exportButton()->isEnabled());
    }

    void closingMidExportCancelsAndWaits() {
        const QString path = dir_.filePath("closed.txt");
        auto dialog = std::make_unique<StepDialog>(path, Ending::WaitForCancel, 1);
        dialog->show();
        QSignalSpy progressed(dialog.get(), &BackgroundExportDialog::progressed);
        QTest::mouseClick(dialog->exportButton(), Qt::LeftButton);
        QTRY_COMPARE_WITH_TIMEOUT(progressed.size(), 1, 10000);
        const auto before = std::chrono::steady_clock::now();
        dialog.reset(); // cancels the job and waits for it: its file is gone
        QVERIFY(std::chrono::steady_clock::now() - before < std::chrono::seconds(10));
        QVERIFY(!QFile::exists(path));
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestBackgroundExportDialog test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_background_export_dialog.moc"
