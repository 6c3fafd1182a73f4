// Cancel really stops a retrieval (C-GET, C-MOVE, WADO-RS) against a real
// Orthanc: the call ends with "cancelled", the PACS stops sending, nothing
// half-written stays, and the next retrieval fetches only the rest. Label pacs.
#include <QTemporaryDir>
#include <QTest>
#include <QThread>

#include <filesystem>
#include <memory>
#include <stop_token>

#include "core/pacs/DicomWebClient.h"
#include "core/pacs/SeriesRetriever.h"
#include "core/pacs/StorageScp.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/SyntheticDicom.h"

using namespace lucent;

namespace {
const char* kStudy = "1.2.826.0.1.3680043.2.1125.951";
const char* kSeries = "1.2.826.0.1.3680043.2.1125.9511";
constexpr int kImages = 60;
constexpr int kCancelAt = 5;
} // namespace

class TestRetrieveCancel : public QObject {
    Q_OBJECT
    std::unique_ptr<test::OrthancServer> orthanc_;
    QTemporaryDir files_;
    PacsNode node_;
    PacsSettings settings_;
    int scpPort_ = 0;

    // Cancels at the kCancelAt-th instance; checks the call says so.
    template <class Retrieve> void cancelAtTheFifth(Retrieve retrieve) {
        std::stop_source stop;
        RetrieveControl control;
        control.stop = stop.get_token();
        control.onProgress = [&](int done, int) {
            if (done >= kCancelAt) {
                stop.request_stop();
            }
        };
        try {
            retrieve(control);
            QFAIL("expected the retrieval to be cancelled");
        } catch (const std::exception& e) {
            QVERIFY2(QString(e.what()).contains("cancelled"), e.what());
        }
    }

    // What a cancel leaves: some but not all instances, all whole and indexed,
    // no temporary files, and nothing more arriving afterwards.
    void checkStopped(StudyStore& store, const QTemporaryDir& dir) {
        const std::size_t right = store.instancesOf(kSeries).size();
        QVERIFY2(right >= kCancelAt - 1 && right < kImages, qPrintable(QString::number(right)));
        QThread::msleep(1500); // the PACS would still be sending if it had not stopped
        QCOMPARE(store.instancesOf(kSeries).size(), right);
        QVERIFY(!store.isComplete(kSeries));
        QVERIFY(std::filesystem::is_empty(dir.filePath("tmp").toStdString()));
        std::size_t onDisk = 0;
        for (const auto& f :
             std::filesystem::directory_iterator(store.seriesFolder(kStudy, kSeries))) {
            QVERIFY(store.contains(f.path().stem().string()));
            ++onDisk;
        }
        QCOMPARE(onDisk, right);
    }

private slots:
    void initTestCase() {
        scpPort_ = test::OrthancServer::freePort();
        orthanc_ = std::make_unique<test::OrthancServer>(scpPort_);
        if (!orthanc_->isRunning()) {
            QSKIP(qPrintable("no test PACS: " + orthanc_->error()));
        }
        node_ = PacsNode::parse(orthanc_->node().toStdString());
        settings_.connectTimeoutSeconds = 5;
        settings_.responseTimeoutSeconds = 10;
        test::SyntheticSeries s;
        s.patientName = "Cancel^Carl";
        s.patientId = "C001";
        s.studyUid = kStudy;
        s.seriesUid = kSeries;
        s.columns = 128;
        s.rows = 128;
        std::vector<glm::dvec3> positions;
        for (int k = 0; k < kImages; ++k) {
            positions.emplace_back(0.0, 0.0, 1.0 * k);
        }
        QStringList files;
        for (const std::string& f : test::writeSeries(files_.path().toStdString(), s, positions)) {
            files << QString::fromStdString(f);
        }
        QVERIFY2(orthanc_->store(files), qPrintable(orthanc_->error()));
    }
    void cleanupTestCase() { orthanc_.reset(); }

    void cancelStopsCGet() {
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        cancelAtTheFifth([&](const RetrieveControl& c) {
            retrieveSeries(node_, settings_, kStudy, kSeries, store, c);
        });
        checkStopped(store, dir);
        const std::size_t kept = store.instancesOf(kSeries).size();
        const RetrieveResult rest = retrieveSeries(node_, settings_, kStudy, kSeries, store);
        QCOMPARE(rest.received, kImages - int(kept));
        QVERIFY(rest.complete);
    }

    void cancelStopsCMove() {
        QTemporaryDir dir;
        const std::filesystem::path root = dir.path().toStdString();
        std::unique_ptr<StorageScp> listening;
        try {
            listening = std::make_unique<StorageScp>(root, StorageScpSettings{"LUCENT", scpPort_});
        } catch (const std::exception& e) {
            QFAIL(e.what());
        }
        const StorageScp& scp = *listening;
        StudyStore store(root);
        cancelAtTheFifth([&](const RetrieveControl& c) {
            moveSeries(node_, settings_, "LUCENT", kStudy, kSeries, store, c);
        });
        checkStopped(store, dir);
        QVERIFY2(scp.received() < kImages, qPrintable(QString::number(scp.received())));
        const std::size_t kept = store.instancesOf(kSeries).size();
        RetrieveResult rest;
        try {
            rest = moveSeries(node_, settings_, "LUCENT", kStudy, kSeries, store);
        } catch (const std::exception& e) {
            QFAIL(e.what());
        }
        QCOMPARE(rest.received, kImages - int(kept));
        QVERIFY(rest.complete);
    }

    void cancelStopsWado() {
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        DicomWebService web;
        web.baseUrl = orthanc_->dicomWebUrl().toStdString();
        cancelAtTheFifth(
            [&](const RetrieveControl& c) { wadoRetrieveSeries(web, kStudy, kSeries, store, c); });
        checkStopped(store, dir);
        const std::size_t kept = store.instancesOf(kSeries).size();
        const RetrieveResult rest = wadoRetrieveSeries(web, kStudy, kSeries, store);
        QCOMPARE(rest.received, kImages - int(kept));
        QVERIFY(rest.complete);
    }
};

QTEST_GUILESS_MAIN(TestRetrieveCancel)
#include "test_retrieve_cancel.moc"
