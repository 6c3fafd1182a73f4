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

using namespace lucent;
namespace fs = std::filesystem;

namespace {

InstanceRecord recordOf(const fs::path& file, const std::string& modality) {
    const InstanceHeader h = readInstanceHeader(file);
    InstanceRecord r;
    r.series.seriesUid = h.seriesUid;
    r.series.studyUid = h.studyUid;
    r.series.modality = modality;
    r.series.patientName = "Phantom";
    r.sopInstanceUid = h.sopInstanceUid;
    return r;
}

void storeCopy(StudyStore& store, const fs::path& file, const std::string& modality) {
    const fs::path temp = store.temporaryFile();
    fs::copy_file(file, temp);
    QVERIFY(store.add(temp, recordOf(file, modality)));
}

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
            storeCopy(store, file, "CT");
        }
        const ReferencedSeries series = readReferencedSeries(test::seriesFiles());
        const std::string ct = series.seriesUid;
        const Volume volume = loadPath(test::kMeasuredSeriesDir);
        std::vector<Measurement> measurements =
            test::everyKind(volume, test::acquiredPlane(series, 20), "axial");
        for (Measurement m : test::everyKind(volume, test::obliquePlane(volume), "oblique")) {
            m.id += 100;
            measurements.push_back(m);
        }

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
        storeCopy(store, foreignFile, "SR");
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
};

QTEST_GUILESS_MAIN(TestMeasurementArchive)
#include "test_measurement_archive.moc"
