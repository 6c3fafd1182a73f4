// Orthanc killed (SIGKILL) in the middle of a retrieval, by C-GET and by
// WADO-RS, against a real Orthanc: the call fails with an error naming the
// PACS and what happened, the series stays incomplete, every stored file is
// whole and indexed, nothing temporary is left; after Orthanc restarts on the
// same storage, `lucent-cli pacs get` fetches only what is missing. Label pacs.
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTest>

#include <memory>

#include "StoreConsistency.h"
#include "core/pacs/DicomWebClient.h"
#include "core/pacs/SeriesRetriever.h"
#include "tests/support/CliRunner.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/SyntheticDicom.h"

using namespace lucent;

namespace {
const char* kStudy = "1.2.826.0.1.3680043.2.1125.961";
const char* kSeries = "1.2.826.0.1.3680043.2.1125.9611";
// 80 images of 512 x 512 x 16 bit (40 MiB): far more than the socket buffers
// hold, so that Orthanc is still sending when it is killed.
constexpr int kImages = 80;
constexpr int kSide = 512;
// Orthanc is killed once this many instances are in the store.
constexpr int kKillAt = 3;

// The counts of `lucent-cli pacs get`'s line for the series: arrived, already stored.
std::pair<int, int> reportedCounts(const QString& out) {
    const auto m = QRegularExpression("(\\d+) instance\\(s\\) arrived, (\\d+) already stored, "
                                      "complete \\((\\d+)/(\\d+)\\)")
                       .match(out);
    return m.hasMatch() ? std::pair{m.captured(1).toInt(), m.captured(2).toInt()}
                        : std::pair{-1, -1};
}
} // namespace

class TestRetrieveInterrupted : public QObject {
    Q_OBJECT
    QTemporaryDir files_;
    QStringList series_;

    // An Orthanc holding the series; null (test skipped or failed) when it cannot start.
    std::unique_ptr<test::OrthancServer> startOrthanc() {
        auto orthanc = std::make_unique<test::OrthancServer>();
        if (!orthanc->isRunning()) {
            QTest::qFail(qPrintable("no test PACS: " + orthanc->error()), __FILE__, __LINE__);
            return nullptr;
        }
        if (!orthanc->store(series_)) {
            QTest::qFail(qPrintable(orthanc->error()), __FILE__, __LINE__);
            return nullptr;
        }
        return orthanc;
    }

    // Retrieves with `retrieve`, killing Orthanc once kKillAt instances are
    // stored; checks the error and what the store holds. The instances stored.
    template <class Retrieve>
    int killInTheMiddle(test::OrthancServer& orthanc, StudyStore& store, Retrieve retrieve,
                        const QString& peer) {
        bool killed = false;
        RetrieveControl control;
        control.onProgress = [&](int done, int) {
            if (done >= kKillAt && !killed) {
                orthanc.kill(); // SIGKILL, as a crash would
                killed = true;
            }
        };
        try {
            retrieve(control);
            QTest::qFail("the retrieval went on although Orthanc was killed", __FILE__, __LINE__);
            return -1;
        } catch (const PacsError& e) {
            const QString message = e.what();
            qInfo().noquote() << "interrupted retrieval:" << message;
            if (!killed || !message.contains(peer) || !message.contains("interrupted") ||
                !message.contains(kSeries) || !message.contains("incomplete")) {
                QTest::qFail(qPrintable("not the error of an interrupted retrieval naming " + peer +
                                        ": " + message),
                             __FILE__, __LINE__);
                return -1;
            }
        }
        const int stored = test::checkStoreConsistent(store, kSeries);
        if (stored < kKillAt || stored >= kImages) {
            QTest::qFail(qPrintable(QString("%1 of %2 instances stored after the kill at the %3rd")
                                        .arg(stored)
                                        .arg(kImages)
                                        .arg(kKillAt)),
                         __FILE__, __LINE__);
            return -1;
        }
        const std::vector<StoredSeries> listed = store.listSeries();
        if (listed.size() != 1 || listed[0].complete || listed[0].expected != kImages ||
            listed[0].stored != stored || store.isComplete(kSeries)) {
            QTest::qFail("the series is not marked incomplete", __FILE__, __LINE__);
            return -1;
        }
        return stored;
    }

    // Restarts Orthanc and runs `lucent-cli pacs get` with `how`: it must
    // fetch exactly the instances the store lacks.
    void resumeWithTheCli(test::OrthancServer& orthanc, StudyStore& store, int stored,
                          const QStringList& how, const QTemporaryDir& dir) {
        QVERIFY2(orthanc.restart(), qPrintable(orthanc.error()));
        const test::CliRun get =
            test::runCli(QStringList{"pacs", "get", "--study", kStudy, "--series", kSeries,
                                     "--store", dir.path()} +
                         how);
        QVERIFY2(get.exitCode == 0, qPrintable(get.out + get.err));
        const auto [arrived, already] = reportedCounts(get.out);
        qInfo().noquote() << QString("after the restart: %1 fetched, %2 already present (of %3)")
                                 .arg(arrived)
                                 .arg(already)
                                 .arg(kImages);
        QCOMPARE(already, stored);
        QCOMPARE(arrived, kImages - stored);
        QCOMPARE(test::checkStoreConsistent(store, kSeries), kImages);
        QVERIFY(store.isComplete(kSeries));
    }

private slots:
    void initTestCase() {
        test::SyntheticSeries s;
        s.patientName = "Interrupted^Ida";
        s.patientId = "I001";
        s.studyUid = kStudy;
        s.seriesUid = kSeries;
        s.columns = kSide;
        s.rows = kSide;
        std::vector<glm::dvec3> positions;
        for (int k = 0; k < kImages; ++k) {
            positions.emplace_back(0.0, 0.0, 1.0 * k);
        }
        for (const std::string& f : test::writeSeries(files_.path().toStdString(), s, positions)) {
            series_ << QString::fromStdString(f);
        }
    }

    void orthancKilledDuringCGet() {
        const auto orthanc = startOrthanc();
        QVERIFY(orthanc);
        const PacsNode node = PacsNode::parse(orthanc->node().toStdString());
        PacsSettings settings;
        settings.connectTimeoutSeconds = 5;
        settings.responseTimeoutSeconds = 10;
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        const int stored = killInTheMiddle(
            *orthanc, store,
            [&](const RetrieveControl& c) {
                retrieveSeries(node, settings, kStudy, kSeries, store, c);
            },
            orthanc->node());
        QVERIFY(stored > 0);
        resumeWithTheCli(*orthanc, store, stored, {"--pacs", orthanc->node()}, dir);
    }

    void orthancKilledDuringWado() {
        const auto orthanc = startOrthanc();
        QVERIFY(orthanc);
        DicomWebService web;
        web.baseUrl = orthanc->dicomWebUrl().toStdString();
        web.timeoutSeconds = 10;
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        const int stored = killInTheMiddle(
            *orthanc, store,
            [&](const RetrieveControl& c) { wadoRetrieveSeries(web, kStudy, kSeries, store, c); },
            orthanc->dicomWebUrl());
        QVERIFY(stored > 0);
        resumeWithTheCli(*orthanc, store, stored,
                         {"--method", "wado", "--wado", orthanc->dicomWebUrl()}, dir);
    }
};

QTEST_GUILESS_MAIN(TestRetrieveInterrupted)
#include "test_retrieve_interrupted.moc"
