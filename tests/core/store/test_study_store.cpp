// The local study store: whole files only, no instance twice, completeness.
#include <QTemporaryDir>
#include <QTest>

#include <QSqlDatabase>
#include <QSqlQuery>

#include <filesystem>
#include <fstream>
#include <thread>

#include "core/store/StudyStore.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

InstanceRecord record(const std::string& sop, const std::string& series = "1.2.3.4") {
    InstanceRecord r;
    r.series.studyUid = "1.2.3";
    r.series.seriesUid = series;
    r.series.modality = "CT";
    r.series.patientName = "Test^Store";
    r.seriesNumber = 2;
    r.sopInstanceUid = sop;
    return r;
}

fs::path incoming(StudyStore& store, const std::string& content) {
    const fs::path p = store.temporaryFile();
    std::ofstream(p, std::ios::binary) << content;
    return p;
}

} // namespace

class TestStudyStore : public QObject {
    Q_OBJECT
private slots:
    void addsEachInstanceOnce() {
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        QVERIFY(store.add(incoming(store, "first"), record("1.2.3.4.1")));
        const fs::path second = incoming(store, "again");
        QVERIFY(!store.add(second, record("1.2.3.4.1")));
        QVERIFY(!fs::exists(second)); // the duplicate's file is not kept anywhere
        QVERIFY(store.contains("1.2.3.4.1"));
        QVERIFY(!store.contains("1.2.3.4.2"));
        const fs::path stored = store.seriesFolder("1.2.3", "1.2.3.4") / "1.2.3.4.1.dcm";
        std::ifstream in(stored);
        std::string content;
        in >> content;
        QCOMPARE(content, std::string("first"));
        QVERIFY(fs::is_empty(dir.path().toStdString() + "/tmp"));
    }

    void completenessFollowsTheExpectedCount() {
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        store.setExpected(record("").series, 2, 3);
        QCOMPARE(store.expected("1.2.3.4"), 3);
        QVERIFY(!store.isComplete("1.2.3.4"));
        for (const char* sop : {"1.2.3.4.1", "1.2.3.4.2", "1.2.3.4.3"}) {
            QVERIFY(store.add(incoming(store, sop), record(sop)));
        }
        QVERIFY(store.isComplete("1.2.3.4"));
        store.remove("1.2.3.4.2");
        QVERIFY(!store.isComplete("1.2.3.4"));
        QCOMPARE(store.instancesOf("1.2.3.4"), (std::set<std::string>{"1.2.3.4.1", "1.2.3.4.3"}));
        QVERIFY(!fs::exists(store.seriesFolder("1.2.3", "1.2.3.4") / "1.2.3.4.2.dcm"));
    }

    void reopeningKeepsTheIndexAndDropsUnfinishedWrites() {
        QTemporaryDir dir;
        const fs::path tmp = fs::path(dir.path().toStdString()) / "tmp";
        {
            StudyStore store(dir.path().toStdString());
            QVERIFY(store.add(incoming(store, "x"), record("1.2.3.4.9")));
        }
        // Left by a process that died (no pid is that large) and by an unknown writer.
        const fs::path dead = tmp / "incoming-999999999-1-1.dcm";
        const fs::path junk = tmp / "junk.part";
        std::ofstream(dead) << "half written";
        std::ofstream(junk) << "?";
        StudyStore writer(dir.path().toStdString());
        const fs::path inFlight = incoming(writer, "being written"); // a living writer's
        StudyStore reopened(dir.path().toStdString());
        QVERIFY(reopened.contains("1.2.3.4.9"));
        QVERIFY(!fs::exists(dead));
        QVERIFY(!fs::exists(junk));
        QVERIFY(fs::exists(inFlight));
        // Two objects on one store never pick the same temporary name.
        QVERIFY(writer.temporaryFile() != reopened.temporaryFile());
    }

    void twoStoresOpenAtOnce() {
        QTemporaryDir a, b;
        StudyStore one(a.path().toStdString());
        StudyStore two(b.path().toStdString());
        QVERIFY(one.add(incoming(one, "1"), record("1.2.3.4.1")));
        QVERIFY(!two.contains("1.2.3.4.1"));
    }

    // The storage SCP's thread and the workstation open a new store at the same
    // moment. Switching to WAL needs the database alone, and SQLite answers a
    // switch it could not make with the old mode instead of an error: without
    // a check the index stayed in rollback mode, where a writer locks readers out.
    void storesOpenedTogetherShareAWalIndex() {
        for (int round = 0; round < 40; ++round) {
            QTemporaryDir dir;
            const fs::path root = dir.path().toStdString();
            std::jthread other([&] { StudyStore s(root); });
            const StudyStore here(root);
            other.join();
            const QString name = QStringLiteral("journal-check-%1").arg(round);
            {
                QSqlDatabase db = QSqlDatabase::addDatabase("QSQLITE", name);
                db.setDatabaseName(QString::fromStdString((root / "index.sqlite").string()));
                QVERIFY(db.open());
                QSqlQuery mode(db);
                QVERIFY(mode.exec("PRAGMA journal_mode") && mode.next());
                QCOMPARE(mode.value(0).toString(), QStringLiteral("wal"));
            }
            QSqlDatabase::removeDatabase(name);
        }
    }

    void indexListsPatientsStudiesAndSeries() {
        QTemporaryDir dir;
        {
            StudyStore store(dir.path().toStdString());
            StudyStore::Batch batch(store); // one transaction, committed when it goes
            InstanceRecord facts = record("");
            facts.studyDescription = "Head";
            facts.accessionNumber = "ACC7";
            facts.patientBirthDate = "19700101";
            store.setExpected(facts, 3);
            for (const char* sop : {"1.2.3.4.1", "1.2.3.4.2"}) {
                QVERIFY(store.add(incoming(store, sop), record(sop)));
            }
            for (int i = 0; i < 40; ++i) { // past the periodic commit inside a batch
                const std::string sop = "1.2.3.5." + std::to_string(i);
                QVERIFY(store.add(incoming(store, sop), record(sop, "1.2.3.5")));
            }
        }
        StudyStore store(dir.path().toStdString());
        const std::vector<StoredSeries> all = store.listSeries();
        QCOMPARE(all.size(), std::size_t(2));
        QCOMPARE(all[0].info.seriesUid, std::string("1.2.3.4"));
        QCOMPARE(all[0].info.patientName, std::string("Test^Store"));
        QCOMPARE(all[0].studyDescription, std::string("Head"));
        QCOMPARE(all[0].accessionNumber, std::string("ACC7"));
        QCOMPARE(all[0].patientBirthDate, std::string("19700101"));
        QCOMPARE(all[0].expected, 3);
        QCOMPARE(all[0].stored, 2);
        QVERIFY(!all[0].complete);
        QCOMPARE(all[1].stored, 40);
        QCOMPARE(all[1].expected, 0); // pushed: nobody said how many
        QVERIFY(!all[1].complete);
        QCOMPARE(all[1].folder, store.seriesFolder("1.2.3", "1.2.3.5"));
    }

    void badInputIsRefused() {
        QTemporaryDir dir;
        const std::string file = dir.filePath("plain-file").toStdString();
        std::ofstream(file) << "not a folder";
        QVERIFY_THROWS_EXCEPTION(StoreError, StudyStore(file + "/store"));
        StudyStore store(dir.filePath("store").toStdString());
        InstanceRecord noUid = record("");
        const fs::path p = incoming(store, "x");
        QVERIFY_THROWS_EXCEPTION(StoreError, store.add(p, noUid));
        QVERIFY(!fs::exists(p));
        // A UID with path characters stays inside the store.
        InstanceRecord hostile = record("../../escape");
        QVERIFY(store.add(incoming(store, "y"), hostile));
        QVERIFY(!fs::exists(dir.filePath("escape.dcm").toStdString()));
    }
};

QTEST_APPLESS_MAIN(TestStudyStore)
#include "test_study_store.moc"
