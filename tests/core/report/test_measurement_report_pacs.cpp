// Measurements on real CT saved as Lucent's SR in a study store, sent with the
// CT to a real Orthanc (C-STORE), retrieved by C-GET into a fresh store and
// shown again equal. Label pacs.
#include <QTemporaryDir>
#include <QTest>

#include "core/exchange/InstanceFiles.h"
#include "core/pacs/InstanceSender.h"
#include "core/pacs/SeriesRetriever.h"
#include "core/report/MeasurementArchive.h"
#include "core/report/MeasurementReport.h"
#include "tests/core/report/MeasuredSeries.h"
#include "tests/core/report/StoredCopies.h"
#include "tests/support/OrthancServer.h"

using namespace lucent;
namespace fs = std::filesystem;

class TestMeasurementReportPacs : public QObject {
    Q_OBJECT

private slots:
    void sentRetrievedAndShownAgain() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        const test::OrthancServer orthanc;
        QVERIFY2(orthanc.isRunning(), qPrintable("no test PACS: " + orthanc.error()));
        const PacsNode node = PacsNode::parse(orthanc.node().toStdString());

        QTemporaryDir here;
        StudyStore store(here.path().toStdString());
        for (const fs::path& file : test::seriesFiles()) {
            QVERIFY(test::storeCopy(store, file, "CT"));
        }
        const ReferencedSeries series = readReferencedSeries(test::seriesFiles());
        const Volume volume = loadPath(test::kMeasuredSeriesDir);
        std::vector<Measurement> measurements = test::onBothPlanes(volume, series, 7);
        MeasurementArchive archive(store);
        const std::string srSop = archive.save(series.seriesUid, measurements);

        // Everything of the study the store holds, the SR among it, to the PACS.
        std::vector<InstanceHeader> sent;
        std::string srSeries;
        for (const StoredSeries& s : store.listSeries()) {
            for (const auto& [sop, file] : store.instanceFiles(s.info.seriesUid)) {
                sent.push_back(readInstanceHeader(file));
                if (sop == srSop) {
                    srSeries = s.info.seriesUid;
                    QCOMPARE(sent.back().sopClassUid, std::string("1.2.840.10008.5.1.4.1.1.88.34"));
                }
            }
        }
        QCOMPARE(sent.size(), std::size_t(29));
        const SendResult result = sendByCStore(node, {}, sent);
        for (const SentInstance& s : result.instances) {
            QVERIFY2(s.outcome == SentInstance::Outcome::Stored, s.message.c_str());
        }

        QTemporaryDir there;
        StudyStore fresh(there.path().toStdString());
        for (const std::string& uid : {series.seriesUid, srSeries}) {
            const RetrieveResult r = retrieveSeries(node, {}, series.studyUid, uid, fresh);
            QVERIFY2(r.complete, uid.c_str());
        }
        MeasurementArchive again(fresh);
        const MeasurementArchive::Loaded loaded = again.load(series.seriesUid);
        QCOMPARE(loaded.reports.size(), std::size_t(1));
        QVERIFY(loaded.notShown.empty());
        test::compareMeasurements(loaded.measurements, measurements);
    }
};

QTEST_GUILESS_MAIN(TestMeasurementReportPacs)
#include "test_measurement_report_pacs.moc"
