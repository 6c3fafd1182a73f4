// Measurements kept as DICOM SR in the local study store as the reader works, in the
// workstation window: a stored real CT (the 28-slice Philips phantom) opened, measured,
// saved without a "save" (after a pause, and at once when the window closes), shown
// again in a new window; another program's SR on the series shown read-only with what
// it holds that Lucent cannot show listed. Offscreen.
#include <QApplication>
#include <QLabel>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>

#include <memory>

#include "core/pacs/PacsConfig.h"
#include "core/report/MeasurementArchive.h"
#include "core/store/StudyStore.h"
#include "tests/core/report/ForeignReport.h"
#include "tests/core/report/MeasuredSeries.h"
#include "tests/core/report/StoredCopies.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/app/MainWindow.h"
#include "ui/app/MeasurementControls.h"
#include "ui/mpr/MeasurementAutosave.h"
#include "ui/mpr/MeasurementList.h"
#include "ui/mpr/SeriesMeasurements.h"

using namespace lucent;
namespace fs = std::filesystem;

class TestMeasurementAutosave : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        QVERIFY(dir_.isValid());
        QStandardPaths::setTestModeEnabled(true);
        QCoreApplication::setOrganizationName(QStringLiteral("lucent-test"));
        QCoreApplication::setApplicationName(QStringLiteral("test_measurement_autosave"));
        QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope,
                           dir_.filePath("settings"));
        storeDir_ = dir_.filePath("store");
        StudyStore store(storeDir_.toStdString());
        for (const fs::path& file : test::seriesFiles()) {
            QVERIFY(test::storeCopy(store, file, "CT"));
        }
        series_ = readReferencedSeries(test::seriesFiles());
        seriesFolder_ = QString::fromStdString(
            store.seriesFolder(series_.studyUid, series_.seriesUid).string());
        QSettings settings(QStringLiteral("lucent"), QStringLiteral("lucent")); // PacsBrowser's
        PacsConfig config = PacsConfig::load(settings);
        config.storeFolder = storeDir_;
        config.save(settings);
    }

    void savedAsTheReaderWorksAndShownAgain() {
        auto window = openStoredSeries();
        QVERIFY(window);
        SeriesMeasurements* m = window->measurements();
        QVERIFY(m != nullptr && m->measurements().empty());
        QSignalSpy saved(window->measurementAutosave(), &MeasurementAutosave::saved);

        const SlicePlane plane = someAxialPlane();
        Measurement d;
        d.kind = MeasurementKind::Distance;
        d.plane = plane;
        d.points = {plane.pointAt(100, 120), plane.pointAt(160, 200)};
        const std::uint64_t id = m->add(d);
        QVERIFY(m->rename(id, "Lesion 1"));
        // One save for both edits, after the pause: no "save" to forget.
        QTRY_COMPARE_WITH_TIMEOUT(saved.count(), 1, 10000);
        QCOMPARE(saved.at(0).at(0).toString(), QString::fromStdString(series_.seriesUid));
        QVERIFY(!saved.at(0).at(1).toString().isEmpty());
        QCOMPARE(storedLabels(), QStringList{"Lesion 1"});

        // Edited and closed at once: saved as the window goes.
        QVERIFY(m->rename(id, "Lesion 1 (target)"));
        window.reset();
        QCOMPARE(storedLabels(), QStringList{"Lesion 1 (target)"});

        // The next session shows it again, editable, equal to the millimetre.
        window = openStoredSeries();
        m = window->measurements();
        QCOMPARE(m->measurements().size(), std::size_t(1));
        const Measurement& back = m->measurements()[0];
        QCOMPARE(back.label, std::string("Lesion 1 (target)"));
        QVERIFY(!back.readOnly);
        QVERIFY(std::abs(measurementLengthMm(back) - measurementLengthMm(d)) < 1e-6);
        QCOMPARE(list(*window)->table()->rowCount(), 1);
        QVERIFY(list(*window)->notShownLabel()->isHidden());

        // Undo back to nothing: Lucent's SR goes from the store.
        QSignalSpy savedAgain(window->measurementAutosave(), &MeasurementAutosave::saved);
        QVERIFY(m->remove(m->measurements()[0].id));
        QTRY_COMPARE_WITH_TIMEOUT(savedAgain.count(), 1, 10000);
        QCOMPARE(savedAgain.at(0).at(1).toString(), QString()); // removed, none written
        QVERIFY(storedLabels().isEmpty());
    }

    void anotherProgramsReportIsShownReadOnly() {
        const fs::path file = fs::path(dir_.filePath("foreign.dcm").toStdString());
        const auto [sop, srSeries] = test::writeForeignReport(file, series_, series_.images[4]);
        QVERIFY(!sop.empty());
        {
            StudyStore store(storeDir_.toStdString());
            QVERIFY(test::storeCopy(store, file, "SR"));
        }
        auto window = openStoredSeries();
        SeriesMeasurements* m = window->measurements();
        QCOMPARE(m->measurements().size(), std::size_t(1));
        QVERIFY(m->measurements()[0].readOnly);
        QCOMPARE(m->measurements()[0].label, std::string("Nodule A"));
        QVERIFY(!m->remove(m->measurements()[0].id)); // read-only
        QLabel* notShown = list(*window)->notShownLabel();
        QVERIFY(!notShown->isHidden());
        QVERIFY2(notShown->text().contains("Nodule"), qPrintable(notShown->text()));
        QCOMPARE(m->notShown().size(), std::size_t(2)); // the finding and the volume
    }

private:
    std::unique_ptr<MainWindow> openStoredSeries() {
        auto window = std::make_unique<MainWindow>();
        window->resize(1400, 900);
        window->show();
        QSignalSpy finished(window.get(), &MainWindow::loadFinished);
        window->openPath(seriesFolder_, QString::fromStdString(series_.seriesUid));
        if (!QTest::qWaitFor([&] { return finished.count() == 1; }, 60000) ||
            !finished.at(0).at(0).toBool() || window->measurements() == nullptr) {
            return nullptr;
        }
        return window;
    }

    static MeasurementList* list(const MainWindow& window) {
        return window.measurementControls()->list();
    }

    SlicePlane someAxialPlane() const {
        const Volume volume = loadPath(test::kMeasuredSeriesDir);
        return standardPlane(volume.geometry(), Orientation::Axial, volumeCentre(volume.geometry()),
                             256, 256);
    }

    // The labels of Lucent's saved measurements, read from the store as a new session would.
    QStringList storedLabels() const {
        StudyStore store(storeDir_.toStdString());
        MeasurementArchive archive(store);
        QStringList labels;
        for (const Measurement& m : archive.load(series_.seriesUid).measurements) {
            if (!m.readOnly) {
                labels << QString::fromStdString(m.label);
            }
        }
        return labels;
    }

    QTemporaryDir dir_;
    QString storeDir_;
    QString seriesFolder_;
    ReferencedSeries series_;
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestMeasurementAutosave test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_measurement_autosave.moc"
