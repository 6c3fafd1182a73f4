// C-ECHO and C-FIND against a real Orthanc on loopback, and the error cases:
// refused, rejected, silent. Label pacs.
#include <QElapsedTimer>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTcpServer>
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>
#include <memory>

#include "core/io/Catalog.h"
#include "core/pacs/DimseQuery.h"
#include "core/pacs/SeriesRetriever.h"
#include "core/pacs/StorageScp.h"
#include "tests/support/CliRunner.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/SyntheticDicom.h"

using namespace lucent;

namespace {

const char* kStudyA = "1.2.826.0.1.3680043.2.1125.901";
const char* kStudyB = "1.2.826.0.1.3680043.2.1125.902";
const char* kStudyC = "1.2.826.0.1.3680043.2.1125.903";

std::vector<std::string> uidsOf(const std::vector<QueryMatch>& m, bool series = false) {
    std::vector<std::string> out;
    for (const QueryMatch& q : m) {
        out.push_back(series ? q.seriesUid : q.studyUid);
    }
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace

class TestDimseQuery : public QObject {
    Q_OBJECT
    std::unique_ptr<test::OrthancServer> orthanc_;
    QTemporaryDir files_;
    PacsNode node_;
    PacsSettings settings_;
    bool realCt_ = false;
    int scpPort_ = 0;

    void write(test::SyntheticSeries s, int images) {
        const std::string dir = files_.filePath(QString::fromStdString(s.seriesUid)).toStdString();
        std::filesystem::create_directories(dir);
        std::vector<glm::dvec3> positions;
        for (int k = 0; k < images; ++k) {
            positions.emplace_back(0.0, 0.0, 2.0 * k);
        }
        test::writeSeries(dir, s, positions);
    }

private slots:
    void initTestCase() {
        scpPort_ = test::OrthancServer::freePort();
        orthanc_ = std::make_unique<test::OrthancServer>(
            scpPort_); // LUCENT on scpPort_ is a move destination
        if (!orthanc_->isRunning()) {
            QSKIP(qPrintable("no test PACS: " + orthanc_->error()));
        }
        node_ = PacsNode::parse(orthanc_->node().toStdString());
        settings_.connectTimeoutSeconds = 5;
        settings_.responseTimeoutSeconds = 10;

        test::SyntheticSeries a;
        a.patientName = "Smith^John";
        a.patientId = "P001";
        a.studyDate = "20240105";
        a.accessionNumber = "ACC1";
        a.studyUid = kStudyA;
        a.seriesUid = "1.2.826.0.1.3680043.2.1125.9011";
        a.seriesNumber = 1;
        write(a, 3);
        a.seriesUid = "1.2.826.0.1.3680043.2.1125.9012";
        a.seriesNumber = 2;
        write(a, 2);
        test::SyntheticSeries b = a;
        b.patientName = "Smith^Jane";
        b.patientId = "P002";
        b.studyDate = "20240320";
        b.accessionNumber = "ACC2";
        b.studyUid = kStudyB;
        b.seriesUid = "1.2.826.0.1.3680043.2.1125.9021";
        b.modality = "MR";
        b.seriesNumber = 5;
        write(b, 2);
        test::SyntheticSeries c = a;
        c.patientName = "Doe^Alice";
        c.patientId = "P003";
        c.studyDate = "20231111";
        c.accessionNumber = "ACC3";
        c.studyUid = kStudyC;
        c.seriesUid = "1.2.826.0.1.3680043.2.1125.9031";
        write(c, 1);
        QStringList files;
        for (const auto& f :
             std::filesystem::recursive_directory_iterator(files_.path().toStdString())) {
            if (f.is_regular_file()) {
                files << QString::fromStdString(f.path().string());
            }
        }
        const std::filesystem::path real =
            std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcmqi_ct3slice";
        for (const char* name : {"01.dcm", "02.dcm", "03.dcm"}) {
            if (std::filesystem::exists(real / name)) {
                files << QString::fromStdString((real / name).string());
                realCt_ = true;
            }
        }
        QVERIFY2(orthanc_->store(files), qPrintable(orthanc_->error()));
    }
    void cleanupTestCase() { orthanc_.reset(); }

    void echoAnswers() { echo(node_, settings_); }

    void echoWithAWrongCalledAeTitleIsRejected() {
        PacsNode wrong = node_;
        wrong.aeTitle = "NOTORTHANC";
        try {
            echo(wrong, settings_);
            QFAIL("expected PacsError");
        } catch (const PacsError& e) {
            QVERIFY2(QString(e.what()).contains("association rejected") &&
                         QString(e.what()).contains("NOTORTHANC"),
                     e.what());
        }
    }

    void echoToAClosedPortIsRefused() {
        PacsNode closed = node_;
        closed.port = test::OrthancServer::freePort();
        QElapsedTimer t;
        t.start();
        try {
            echo(closed, settings_);
            QFAIL("expected PacsError");
        } catch (const PacsError& e) {
            QVERIFY2(QString(e.what()).contains("connection refused"), e.what());
        }
        QVERIFY(t.elapsed() < 3000);
    }

    void echoToASilentServerTimesOut() {
        // Accepts TCP connections (the kernel does, from the backlog) and never answers.
        QTcpServer silent;
        QVERIFY(silent.listen(QHostAddress::LocalHost, 0));
        PacsNode node{"SILENT", "127.0.0.1", silent.serverPort()};
        PacsSettings quick = settings_;
        quick.connectTimeoutSeconds = 2;
        QElapsedTimer t;
        t.start();
        try {
            echo(node, quick);
            QFAIL("expected PacsError");
        } catch (const PacsError& e) {
            QVERIFY2(QString(e.what()).contains("timeout"), e.what());
        }
        QVERIFY2(t.elapsed() < 6000, qPrintable(QString::number(t.elapsed())));
    }

    void findStudiesByPatientNameWildcard() {
        QueryFilter f;
        f.patientName = "Smith*";
        const auto m = find(node_, settings_, QueryLevel::Study, f);
        QCOMPARE(uidsOf(m), (std::vector<std::string>{kStudyA, kStudyB}));
        for (const QueryMatch& q : m) {
            if (q.studyUid == kStudyA) {
                QCOMPARE(q.patientName, std::string("Smith^John"));
                QCOMPARE(q.instances, 5);
                QCOMPARE(q.accessionNumber, std::string("ACC1"));
            }
        }
    }

    void findByPatientIdAccessionAndStudyUid() {
        QueryFilter byId;
        byId.patientId = "P003";
        QCOMPARE(uidsOf(find(node_, settings_, QueryLevel::Study, byId)),
                 (std::vector<std::string>{kStudyC}));
        QueryFilter byAccession;
        byAccession.accessionNumber = "ACC2";
        QCOMPARE(uidsOf(find(node_, settings_, QueryLevel::Study, byAccession)),
                 (std::vector<std::string>{kStudyB}));
        QueryFilter byUid;
        byUid.studyUid = kStudyA;
        QCOMPARE(uidsOf(find(node_, settings_, QueryLevel::Study, byUid)),
                 (std::vector<std::string>{kStudyA}));
    }

    void findByModalities() {
        QueryFilter mr;
        mr.modalities = {"MR"};
        QCOMPARE(uidsOf(find(node_, settings_, QueryLevel::Study, mr)),
                 (std::vector<std::string>{kStudyB}));
        QueryFilter both;
        both.modalities = {"CT", "MR"};
        both.patientName = "*^*";
        const auto m = find(node_, settings_, QueryLevel::Study, both);
        QVERIFY(m.size() >= 3);
        const auto uids = uidsOf(m);
        for (const char* uid : {kStudyA, kStudyB, kStudyC}) {
            QVERIFY(std::find(uids.begin(), uids.end(), uid) != uids.end());
        }
    }

    void findByDateRange() {
        QueryFilter january;
        january.dateRange = "20240101-20240131";
        QCOMPARE(uidsOf(find(node_, settings_, QueryLevel::Study, january)),
                 (std::vector<std::string>{kStudyA}));
        QueryFilter fromMarch;
        fromMarch.dateRange = "20240301-";
        QVERIFY(uidsOf(find(node_, settings_, QueryLevel::Study, fromMarch)) ==
                (std::vector<std::string>{kStudyB}));
        QueryFilter bad;
        bad.dateRange = "2024-01-01";
        QVERIFY_THROWS_EXCEPTION(PacsError, find(node_, settings_, QueryLevel::Study, bad));
    }

    void findSeriesOfAStudy() {
        QueryFilter f;
        f.studyUid = kStudyA;
        const auto m = find(node_, settings_, QueryLevel::Series, f);
        QCOMPARE(m.size(), std::size_t(2));
        QCOMPARE(m[0].seriesNumber, 1);
        QCOMPARE(m[0].instances, 3);
        QCOMPARE(m[1].seriesNumber, 2);
        QCOMPARE(m[1].instances, 2);
        QCOMPARE(m[0].modality, std::string("CT"));
        // Without a study UID the matching studies' series are listed.
        QueryFilter jane;
        jane.patientName = "Smith^Jane";
        const auto s = find(node_, settings_, QueryLevel::Series, jane);
        QCOMPARE(s.size(), std::size_t(1));
        QCOMPARE(s[0].modality, std::string("MR"));
        QCOMPARE(s[0].studyUid, std::string(kStudyB));
    }

    void findPatients() {
        QueryFilter f;
        f.patientName = "Smith*";
        const auto m = find(node_, settings_, QueryLevel::Patient, f);
        QCOMPARE(m.size(), std::size_t(2));
        QCOMPARE(m[0].level, QueryLevel::Patient);
    }

    void realCtIsFound() {
        if (!realCt_) {
            QSKIP("real test data not found: ../shared/data/dcmqi_ct3slice");
        }
        QueryFilter f;
        f.modalities = {"CT"};
        f.patientName = "*";
        bool found = false;
        for (const QueryMatch& m : find(node_, settings_, QueryLevel::Study, f)) {
            found = found || (m.instances == 3 && m.studyUid != kStudyA && m.studyUid != kStudyC);
        }
        QVERIFY(found);
    }

    void retrieveFetchesOnlyWhatIsMissing() {
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        const std::string series = "1.2.826.0.1.3680043.2.1125.9011";
        int progress = 0;
        RetrieveControl control;
        control.onProgress = [&](int done, int) { progress = done; };
        const RetrieveResult first =
            retrieveSeries(node_, settings_, kStudyA, series, store, control);
        QCOMPARE(first.expected, 3);
        QCOMPARE(first.received, 3);
        QCOMPARE(first.alreadyStored, 0);
        QVERIFY(first.complete);
        QCOMPARE(progress, 3);
        // What arrived is whole DICOM that loads as the series it was.
        const Volume v = loadPath(first.folder);
        QCOMPARE(v.dims(), glm::ivec3(8, 6, 3));
        QCOMPARE(v.seriesUid, series);

        const RetrieveResult again = retrieveSeries(node_, settings_, kStudyA, series, store);
        QCOMPARE(again.received, 0);
        QCOMPARE(again.alreadyStored, 3);
        QVERIFY(again.complete);

        // An instance lost from the store is the only one fetched next time.
        const std::string lost = *store.instancesOf(series).begin();
        store.remove(lost);
        QVERIFY(!store.isComplete(series));
        const RetrieveResult repaired = retrieveSeries(node_, settings_, kStudyA, series, store);
        QCOMPARE(repaired.received, 1);
        QCOMPARE(repaired.alreadyStored, 2);
        QVERIFY(repaired.complete && store.contains(lost));
    }

    void moveIntoTheStoreThroughLucentsStorageScp() {
        QTemporaryDir dir;
        const std::filesystem::path root = dir.path().toStdString();
        StorageScp scp(root, {"LUCENT", scpPort_});
        StudyStore store(root);
        const std::string series = "1.2.826.0.1.3680043.2.1125.9012";
        const RetrieveResult r = moveSeries(node_, settings_, "LUCENT", kStudyA, series, store);
        QCOMPARE(r.expected, 2);
        QCOMPARE(r.received, 2);
        QVERIFY(r.complete);
        QCOMPARE(scp.received(), 2);
        QCOMPARE(loadPath(r.folder).dims(), glm::ivec3(8, 6, 2));
        const RetrieveResult again = moveSeries(node_, settings_, "LUCENT", kStudyA, series, store);
        QCOMPARE(again.received, 0);
        QCOMPARE(again.alreadyStored, 2);
        QCOMPARE(scp.received(), 2); // nothing was sent twice
        // Lucent's SCP answers C-ECHO and takes pushes (C-STORE) too.
        echo(PacsNode{"LUCENT", "127.0.0.1", scpPort_}, settings_);
        QProcess push;
        push.start("storescu", {"-aec", "LUCENT", "127.0.0.1", QString::number(scpPort_),
                                files_.filePath("1.2.826.0.1.3680043.2.1125.9031/img0.dcm")});
        QVERIFY(push.waitForFinished(30000) && push.exitCode() == 0);
        QVERIFY(
            store.contains(store.instancesOf("1.2.826.0.1.3680043.2.1125.9031").empty()
                               ? std::string("-")
                               : *store.instancesOf("1.2.826.0.1.3680043.2.1125.9031").begin()));
        QCOMPARE(scp.received(), 3);
    }

    void moveToAnUnknownDestinationSaysSo() {
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        try {
            moveSeries(node_, settings_, "NOBODY", kStudyA, "1.2.826.0.1.3680043.2.1125.9012",
                       store);
            QFAIL("expected PacsError");
        } catch (const PacsError& e) {
            // 0xA801 says "destination unknown"; Orthanc sends a generic failure: either way the
            // message names it.
            QVERIFY2(QString(e.what()).contains("'NOBODY'") &&
                         QString(e.what()).contains("move destination"),
                     e.what());
        }
    }

    void retrievingAnUnknownSeriesSaysSo() {
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        try {
            retrieveSeries(node_, settings_, kStudyA, "1.2.3.999", store);
            QFAIL("expected PacsError");
        } catch (const PacsError& e) {
            QVERIFY2(QString(e.what()).contains("1.2.3.999") &&
                         QString(e.what()).contains("no instances"),
                     e.what());
        }
    }

    void pacsKilledMidRetrievalLeavesNothingHalfWritten() {
        // A series of 40 images; Orthanc is killed after the 10th has arrived.
        test::SyntheticSeries s;
        s.patientName = "Kill^Test";
        s.patientId = "P009";
        s.studyUid = "1.2.826.0.1.3680043.2.1125.909";
        s.seriesUid = "1.2.826.0.1.3680043.2.1125.9091";
        const std::string dir = files_.filePath("killed").toStdString();
        std::filesystem::create_directories(dir);
        std::vector<glm::dvec3> positions;
        for (int k = 0; k < 40; ++k) {
            positions.emplace_back(0.0, 0.0, 1.0 * k);
        }
        QStringList files;
        for (const std::string& f : test::writeSeries(dir, s, positions)) {
            files << QString::fromStdString(f);
        }
        QVERIFY2(orthanc_->store(files), qPrintable(orthanc_->error()));

        QTemporaryDir storeDir;
        StudyStore store(storeDir.path().toStdString());
        RetrieveControl killer;
        killer.onProgress = [&](int done, int) {
            if (done == 10) {
                orthanc_->kill();
            }
        };
        QVERIFY_THROWS_EXCEPTION(
            PacsError, retrieveSeries(node_, settings_, s.studyUid, s.seriesUid, store, killer));
        const auto stored = store.instancesOf(s.seriesUid);
        QVERIFY2(stored.size() >= 10 && stored.size() < 40,
                 qPrintable(QString::number(stored.size())));
        QVERIFY(!store.isComplete(s.seriesUid));
        QCOMPARE(store.expected(s.seriesUid), 40);
        // Nothing half-written: tmp/ is empty and every file in the series folder is indexed and
        // whole.
        QVERIFY(std::filesystem::is_empty(storeDir.filePath("tmp").toStdString()));
        std::size_t onDisk = 0;
        for (const auto& f :
             std::filesystem::directory_iterator(store.seriesFolder(s.studyUid, s.seriesUid))) {
            ++onDisk;
            QVERIFY(stored.count(f.path().stem().string()) == 1);
        }
        QCOMPARE(onDisk, stored.size());
        QCOMPARE(loadPath(store.seriesFolder(s.studyUid, s.seriesUid)).dims().z,
                 int(stored.size()));

        // The PACS comes back: only the rest is fetched.
        QVERIFY2(orthanc_->restart(), qPrintable(orthanc_->error()));
        const RetrieveResult rest =
            retrieveSeries(node_, settings_, s.studyUid, s.seriesUid, store);
        QCOMPARE(rest.received, 40 - int(stored.size()));
        QCOMPARE(rest.alreadyStored, int(stored.size()));
        QVERIFY(rest.complete);
    }

    void commandLine() {
        const QString pacs = orthanc_->node();
        const test::CliRun ok = test::runCli({"pacs", "echo", "--pacs", pacs});
        QVERIFY2(ok.exitCode == 0 && ok.out.contains("answered C-ECHO"), qPrintable(ok.err));
        const test::CliRun found =
            test::runCli({"pacs", "find", "--pacs", pacs, "--patient-name", "Smith*", "--json"});
        QCOMPARE(found.exitCode, 0);
        const QJsonArray list = QJsonDocument::fromJson(found.out.toUtf8()).array();
        QCOMPARE(list.size(), 2);
        QCOMPARE(list[0].toObject()["level"].toString(), QString("study"));
        const test::CliRun series =
            test::runCli({"pacs", "find", "--pacs", pacs, "--level", "series", "--study", kStudyA});
        QVERIFY2(series.exitCode == 0 && series.out.contains("2 match(es)"),
                 qPrintable(series.out + series.err));
        const QString closed = QString("ORTHANC@127.0.0.1:%1").arg(test::OrthancServer::freePort());
        const test::CliRun refused = test::runCli({"pacs", "echo", "--pacs", closed});
        QCOMPARE(refused.exitCode, 4);
        QVERIFY(refused.err.contains("connection refused"));
        QCOMPARE(test::runCli({"pacs", "echo"}).exitCode, 2);
        QCOMPARE(test::runCli({"pacs", "echo", "--pacs", "no-at-sign"}).exitCode, 2);
        QCOMPARE(test::runCli({"pacs", "echo", "--pacs", pacs, "--aet", "WAY_TOO_LONG_FOR_AN_AE"})
                     .exitCode,
                 2);
        QCOMPARE(test::runCli({"pacs", "find", "--pacs", pacs, "--date", "last week"}).exitCode, 2);
        QCOMPARE(test::runCli({"pacs", "find", "--pacs", pacs, "--level", "image"}).exitCode, 2);
        QCOMPARE(test::runCli({"pacs", "fetch"}).exitCode, 2);
        QTemporaryDir store;
        const test::CliRun get = test::runCli(
            {"pacs", "get", "--pacs", pacs, "--study", kStudyA, "--store", store.path()});
        QVERIFY2(get.exitCode == 0, qPrintable(get.err));
        QVERIFY2(get.out.contains("3 instance(s) arrived") &&
                     get.out.contains("2 instance(s) arrived") && get.out.count("complete") == 2,
                 qPrintable(get.out));
        const test::CliRun info = test::runCli({"info", store.path()});
        QVERIFY2(info.exitCode == 0 && info.out.contains("8x6x3") && info.out.contains("8x6x2"),
                 qPrintable(info.out));
        QTemporaryDir moved;
        const test::CliRun move = test::runCli(
            {"pacs", "get", "--pacs", pacs, "--study", kStudyA, "--method", "cmove", "--aet",
             "LUCENT", "--port", QString::number(scpPort_), "--store", moved.path()});
        QVERIFY2(move.exitCode == 0 && move.out.count("complete") == 2,
                 qPrintable(move.out + move.err));
        // C-MOVE, not C-GET: to a destination the PACS does not know, nothing moves.
        QTemporaryDir stranger;
        const test::CliRun unknownDestination = test::runCli(
            {"pacs", "get", "--pacs", pacs, "--study", kStudyA, "--method", "cmove", "--aet",
             "STRANGER", "--port", QString::number(test::OrthancServer::freePort()), "--store",
             stranger.path()});
        QVERIFY2(unknownDestination.exitCode == 4 && unknownDestination.err.contains("STRANGER"),
                 qPrintable(unknownDestination.out + unknownDestination.err));
        QCOMPARE(test::runCli({"pacs", "get", "--pacs", pacs}).exitCode, 2);
        QCOMPARE(
            test::runCli({"pacs", "get", "--pacs", pacs, "--study", kStudyA, "--method", "wado"})
                .exitCode,
            2);
    }
};

QTEST_GUILESS_MAIN(TestDimseQuery)
#include "test_dimse_query.moc"
