// QIDO-RS and WADO-RS against Orthanc's DICOMweb plugin on loopback. Label pacs.
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>
#include <memory>

#include "core/io/Catalog.h"
#include "core/pacs/DicomWebClient.h"
#include "tests/support/CliRunner.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/SyntheticDicom.h"

using namespace lucent;

namespace {
const char* kStudy = "1.2.826.0.1.3680043.2.1125.801";
const char* kSeriesCt = "1.2.826.0.1.3680043.2.1125.8011";
const char* kSeriesMr = "1.2.826.0.1.3680043.2.1125.8012";
} // namespace

class TestDicomWeb : public QObject {
    Q_OBJECT
    std::unique_ptr<test::OrthancServer> orthanc_;
    QTemporaryDir files_;
    DicomWebService service_;

private slots:
    void initTestCase() {
        orthanc_ = std::make_unique<test::OrthancServer>();
        if (!orthanc_->isRunning()) {
            QSKIP(qPrintable("no test PACS: " + orthanc_->error()));
        }
        service_.baseUrl = orthanc_->dicomWebUrl().toStdString();
        service_.timeoutSeconds = 10;
        test::SyntheticSeries s;
        s.patientName = "Web^Walter";
        s.patientId = "W001";
        s.studyDate = "20250210";
        s.accessionNumber = "WEB1";
        s.studyUid = kStudy;
        s.seriesUid = kSeriesCt;
        s.seriesNumber = 4;
        QStringList files;
        std::vector<glm::dvec3> positions;
        for (int k = 0; k < 5; ++k) {
            positions.emplace_back(0.0, 0.0, 1.5 * k);
        }
        for (const std::string& f :
             test::writeSeries(files_.path().toStdString(), s, positions, "ct")) {
            files << QString::fromStdString(f);
        }
        s.seriesUid = kSeriesMr;
        s.modality = "MR";
        s.seriesNumber = 7;
        positions.resize(2);
        for (const std::string& f :
             test::writeSeries(files_.path().toStdString(), s, positions, "mr")) {
            files << QString::fromStdString(f);
        }
        QVERIFY2(orthanc_->store(files), qPrintable(orthanc_->error()));
    }
    void cleanupTestCase() { orthanc_.reset(); }

    void searchStudiesAndSeries() {
        QueryFilter f;
        f.patientName = "Web*";
        const auto studies = qidoSearch(service_, QueryLevel::Study, f);
        QCOMPARE(studies.size(), std::size_t(1));
        QCOMPARE(studies[0].studyUid, std::string(kStudy));
        QCOMPARE(studies[0].patientName, std::string("Web^Walter"));
        QCOMPARE(studies[0].accessionNumber, std::string("WEB1"));
        QueryFilter byDate;
        byDate.dateRange = "20250201-20250228";
        QCOMPARE(qidoSearch(service_, QueryLevel::Study, byDate).size(), std::size_t(1));
        byDate.dateRange = "20240101-20240131";
        QVERIFY(qidoSearch(service_, QueryLevel::Study, byDate).empty());
        QueryFilter inStudy;
        inStudy.studyUid = kStudy;
        const auto series = qidoSearch(service_, QueryLevel::Series, inStudy);
        QCOMPARE(series.size(), std::size_t(2));
        QCOMPARE(series[0].seriesNumber, 4);
        QCOMPARE(series[0].modality, std::string("CT"));
        QCOMPARE(series[1].modality, std::string("MR"));
        inStudy.modalities = {"MR"};
        QCOMPARE(qidoSearch(service_, QueryLevel::Series, inStudy).size(), std::size_t(1));
    }

    void retrieveFetchesOnlyWhatIsMissing() {
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        const RetrieveResult r = wadoRetrieveSeries(service_, kStudy, kSeriesCt, store);
        QCOMPARE(r.expected, 5);
        QCOMPARE(r.received, 5);
        QVERIFY(r.complete);
        const Volume v = loadPath(r.folder);
        QCOMPARE(v.dims(), glm::ivec3(8, 6, 5));
        QVERIFY(std::filesystem::is_empty(dir.filePath("tmp").toStdString()));
        const std::string lost = *store.instancesOf(kSeriesCt).begin();
        store.remove(lost);
        const RetrieveResult again = wadoRetrieveSeries(service_, kStudy, kSeriesCt, store);
        QCOMPARE(again.received, 1);
        QCOMPARE(again.alreadyStored, 4);
        QVERIFY(again.complete && store.contains(lost));
    }

    void failuresSayWhat() {
        DicomWebService refused = service_;
        refused.baseUrl = QString("http://127.0.0.1:%1/dicom-web")
                              .arg(test::OrthancServer::freePort())
                              .toStdString();
        try {
            qidoSearch(refused, QueryLevel::Study, {});
            QFAIL("expected PacsError");
        } catch (const PacsError& e) {
            QVERIFY2(QString(e.what()).contains("connection refused"), e.what());
        }
        DicomWebService wrongPath = service_;
        wrongPath.baseUrl =
            QString("http://127.0.0.1:%1/no-such-root").arg(orthanc_->httpPort()).toStdString();
        try {
            qidoSearch(wrongPath, QueryLevel::Study, {});
            QFAIL("expected PacsError");
        } catch (const PacsError& e) {
            QVERIFY2(QString(e.what()).contains("HTTP 404"), e.what());
        }
    }

    void commandLine() {
        QTemporaryDir store;
        const QString wado = orthanc_->dicomWebUrl();
        const test::CliRun get = test::runCli({"pacs", "get", "--method", "wado", "--wado", wado,
                                               "--study", kStudy, "--store", store.path()});
        QVERIFY2(get.exitCode == 0, qPrintable(get.err));
        QVERIFY2(get.out.contains("5 instance(s) arrived") &&
                     get.out.contains("2 instance(s) arrived"),
                 qPrintable(get.out));
        const test::CliRun found =
            test::runCli({"pacs", "find", "--wado", wado, "--patient-name", "Web*"});
        QVERIFY2(found.exitCode == 0 && found.out.contains("1 match(es)"),
                 qPrintable(found.out + found.err));
        QCOMPARE(test::runCli({"pacs", "get", "--method", "wado", "--study", kStudy}).exitCode, 2);
    }
};

QTEST_GUILESS_MAIN(TestDicomWeb)
#include "test_dicomweb.moc"
