// The measurements of a real CT series kept in the study store as Lucent's SR:
// saved, replaced (one SR, never a half-written file in the index), read again
// by a fresh archive, shown beside a foreign SR's read-only ones, and removed.
#include <QTemporaryDir>
#include <QTest>

#include "core/exchange/InstanceFiles.h"
#include "core/report/MeasurementArchive.h"
#include "core/report/MeasurementReport.h"
#include "tests/core/report/ForeignReport.h"
#include "tests/core/report/MeasuredSeries.h"
#include "tests/core/report/StoredCopies.h"
#include "tests/support/CliRunner.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

// Every SR series of the store with its instance files; each file the index names exists.
std::vector<std::pair<std::string, fs::path>> reportsIn(const StudyStore& store) {
    std::vector<std::pair<std::string, fs::path>> out;
    for (const StoredSeries& s : store.listSeries()) {
        for (const auto& [sop, file] : store.instanceFiles(s.info.seriesUid)) {
            if (!fs::exists(file)) {
                qWarning("the index names a missing file: %s", file.c_str());
                return {};
            }
            if (s.info.modality == "SR") {
                out.emplace_back(sop, file);
            }
        }
    }
    return out;
}

} // namespace

class TestMeasurementArchive : public QObject {
    Q_OBJECT

private slots:
    void saveReplaceRemoveReload() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        for (const fs::path& file : test::seriesFiles()) {
            QVERIFY(test::storeCopy(store, file, "CT"));
        }
        const ReferencedSeries series = readReferencedSeries(test::seriesFiles());
        const std::string ct = series.seriesUid;
        const Volume volume = loadPath(test::kMeasuredSeriesDir);
        std::vector<Measurement> measurements = test::onBothPlanes(volume, series, 20);

        MeasurementArchive archive(store);
        QVERIFY(archive.load(ct).measurements.empty());
        const std::string first = archive.save(ct, measurements);
        auto reports = reportsIn(store);
        QCOMPARE(reports.size(), std::size_t(1));
        QCOMPARE(reports[0].first, first);
        const fs::path firstFile = reports[0].second;
        MeasurementArchive::Loaded loaded = archive.load(ct);
        test::compareMeasurements(loaded.measurements, measurements);
        QVERIFY(loaded.notShown.empty());
        // The SR is an instance of the CT's study, in its own series.
        QCOMPARE(store.studyOf(readMeasurementReport(firstFile).seriesUid), series.studyUid);

        // An edit: saved again, it replaces the SR (one instance, a new UID, the old file gone).
        measurements.erase(measurements.begin() + 1);
        measurements[0].label = "renamed";
        measurements[0].points[1] += glm::dvec3(0.125, -0.25, 0.0);
        const std::string second = archive.save(ct, measurements);
        QVERIFY(second != first);
        reports = reportsIn(store);
        QCOMPARE(reports.size(), std::size_t(1));
        QCOMPARE(reports[0].first, second);
        QVERIFY(!fs::exists(firstFile));
        MeasurementArchive fresh(store); // as the next session opens the series
        test::compareMeasurements(fresh.load(ct).measurements, measurements);

        // A foreign SR of the same series: shown read-only beside Lucent's, never copied into it.
        const fs::path foreignFile = fs::path(dir.path().toStdString()) / "foreign.dcm";
        const auto [foreignSop, foreignSeries] =
            test::writeForeignReport(foreignFile, series, series.images[4]);
        QVERIFY(!foreignSop.empty());
        QVERIFY(test::storeCopy(store, foreignFile, "SR"));
        loaded = fresh.load(ct);
        QCOMPARE(loaded.measurements.size(), measurements.size() + 1);
        QCOMPARE(loaded.reports.size(), std::size_t(2));
        const auto foreign = std::find_if(loaded.measurements.begin(), loaded.measurements.end(),
                                          [](const Measurement& m) { return m.readOnly; });
        QVERIFY(foreign != loaded.measurements.end());
        QCOMPARE(foreign->label, std::string("Nodule A"));
        QCOMPARE(loaded.notShown.size(), std::size_t(2)); // the finding and the volume
        const std::string third = fresh.save(ct, loaded.measurements);
        reports = reportsIn(store);
        QCOMPARE(reports.size(), std::size_t(2));
        QCOMPARE(fresh.load(ct).measurements.size(), measurements.size() + 1);

        // Nothing left to save: Lucent's SR goes, the foreign one stays.
        QCOMPARE(archive.save(ct, {*foreign}), std::string());
        reports = reportsIn(store);
        QCOMPARE(reports.size(), std::size_t(1));
        QCOMPARE(reports[0].first, foreignSop);
        // Its emptied series leaves the study browser's list too.
        QCOMPARE(store.listSeries().size(), std::size_t(2)); // the CT and the foreign SR
        loaded = archive.load(ct);
        QCOMPARE(loaded.measurements.size(), std::size_t(1));
        QVERIFY(loaded.measurements[0].readOnly);

        // A series the store does not hold: an error naming it, nothing stored changes.
        try {
            archive.save("1.2.3.4.5", measurements);
            QFAIL("saved measurements of a series that is not stored");
        } catch (const ReportError& e) {
            QVERIFY2(QString(e.what()).contains("1.2.3.4.5"), e.what());
        }
        QCOMPARE(reportsIn(store).size(), std::size_t(1));
        QVERIFY(third != second);
    }

    void commandLine() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        QTemporaryDir dir;
        const QString storeDir = dir.path() + "/store";
        const ReferencedSeries series = readReferencedSeries(test::seriesFiles());
        const Volume volume = loadPath(test::kMeasuredSeriesDir);
        fs::path srFile;
        {
            StudyStore store(storeDir.toStdString());
            for (const fs::path& file : test::seriesFiles()) {
                QVERIFY(test::storeCopy(store, file, "CT"));
            }
            MeasurementArchive archive(store);
            archive.save(series.seriesUid,
                         test::everyKind(volume, test::obliquePlane(volume), "o"));
            srFile = reportsIn(store).at(0).second;
        }
        const QString uid = QString::fromStdString(series.seriesUid);
        test::CliRun run = test::runCli({"measurements", "--series", uid, "--store", storeDir});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        QVERIFY2(run.out.contains("6 measurement(s)"), qPrintable(run.out));
        QVERIFY2(run.out.contains("Cobb angle  o Cobb"), qPrintable(run.out));
        run = test::runCli({"measurements", QString::fromStdString(srFile.string()), "--json"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        QCOMPARE(run.out.count("\"read_only\": false"), 6);
        const QString ct = QString::fromStdString(series.images[0].file.string());
        run = test::runCli({"measurements", ct});
        QCOMPARE(run.exitCode, 3);
        QVERIFY2(run.err.contains(ct) && run.err.contains("not a structured report"),
                 qPrintable(run.err));
        QCOMPARE(test::runCli({"measurements"}).exitCode, 2);
    }
};

QTEST_GUILESS_MAIN(TestMeasurementArchive)
#include "test_measurement_archive.moc"
