// Priors found and fetched by themselves: a real Orthanc holds four more studies of the
// real CT's patient (made from a real CT with DCMTK: new UIDs, other dates, one of another
// body part); PriorsForStudy, asked for prior 1 of the real CT, lists every study from
// C-FIND and QIDO-RS (a dead node named, the others still asked), picks the most recent
// comparable one, fetches it into the store by C-GET or WADO-RS, and fetches nothing the
// second time. Also the comparison rule on its own. Label pacs.
#include <QCoreApplication>
#include <QSignalSpy>
#include <QTcpServer>
#include <QTemporaryDir>
#include <QTest>

#include <dcmtk/dcmdata/dctk.h>

#include "core/io/Catalog.h"
#include "core/pacs/PacsService.h"
#include "core/pacs/PriorsForStudy.h"
#include "core/store/StudyStore.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/PriorStudy.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

const char* kCurrent = "dcm_qa_ct/Philips_S21570/S2020"; // CT BRAIN of 2015-02-06
const char* kSource = "dcm_qa_ct/Philips_S21570/S2010";  // 28 slices: quick to move

void setBodyPart(const test::PriorStudy& study, const char* part) {
    for (const auto& file : study.files) {
        DcmFileFormat f;
        QVERIFY(f.loadFile(file.c_str()).good());
        f.loadAllDataIntoMemory(); // written over below
        f.getDataset()->putAndInsertString(DCM_BodyPartExamined, part);
        QVERIFY(f.saveFile(file.c_str(), EXS_LittleEndianExplicit).good());
    }
}

PatientSeries series(const char* modality, const char* bodyPart) {
    PatientSeries s;
    s.seriesUid = std::string("1.2.3.") + modality + bodyPart;
    s.modality = modality;
    s.bodyPart = bodyPart;
    return s;
}

} // namespace

class TestPriors : public QObject {
    Q_OBJECT

private slots:
    void comparableByModalityAndRegion() {
        const CurrentStudy ct{"P", "9", "CT", "CHEST", "20200101", ""};
        PatientStudy thorax;
        thorax.series = {series("CT", "THORAX"), series("SR", "")};
        QVERIFY(isComparable(thorax, ct));
        PatientStudy head;
        head.series = {series("CT", "HEAD")};
        QVERIFY(!isComparable(head, ct));
        PatientStudy mr;
        mr.series = {series("MR", "CHEST")};
        QVERIFY(!isComparable(mr, ct));
        PatientStudy unsaid; // the store does not keep body parts: modality decides
        unsaid.series = {series("CT", "")};
        QVERIFY(isComparable(unsaid, ct));
        QCOMPARE(bodyRegion("brain "), std::string("HEAD"));

        // Newest first; priors numbered among the comparable studies before the current.
        std::vector<PatientStudy> all(4);
        all[0].studyUid = "old", all[0].studyDate = "20100101", all[0].series = thorax.series;
        all[1].studyUid = "9", all[1].studyDate = "20200101", all[1].studyTime = "1200";
        all[1].series = thorax.series;
        all[2].studyUid = "head", all[2].studyDate = "20190101", all[2].series = head.series;
        all[3].studyUid = "sameDay", all[3].studyDate = "20200101", all[3].studyTime = "0800";
        all[3].series = thorax.series;
        CurrentStudy later = ct;
        later.studyTime = "1200";
        orderPriors(all, later);
        QCOMPARE(all[0].studyUid, std::string("9"));
        QCOMPARE(all[0].order, 0);
        QCOMPARE(all[1].studyUid, std::string("sameDay"));
        QCOMPARE(all[1].order, 1);
        QCOMPARE(all[2].studyUid, std::string("head"));
        QCOMPARE(all[2].order, -1);
        QCOMPARE(all[3].order, 2);
    }

    void initTestCase() {
        if (!std::filesystem::exists(test::kRealData / kCurrent)) {
            return; // the rule's test above still runs; the others skip
        }
        orthanc_ = std::make_unique<test::OrthancServer>();
        QVERIFY2(orthanc_->isRunning(), qPrintable("Orthanc is needed: " + orthanc_->error()));
        const SeriesEntry entry = scanPath((test::kRealData / kCurrent).string()).series.front();
        current_ = {entry.patientId, entry.studyUid,  entry.modality,
                    entry.bodyPart,  entry.studyDate, entry.studyTime};
        QCOMPARE(current_.studyDate, std::string("20150206"));
        const std::filesystem::path source = test::kRealData / kSource;
        const std::string dir = made_.path().toStdString();
        older_ = test::writePriorStudy(source, dir + "/older", "20100101");
        newer_ = test::writePriorStudy(source, dir + "/newer", "20140101");
        test::PriorStudy chest = test::writePriorStudy(source, dir + "/chest", "20141201");
        setBodyPart(chest, "CHEST");
        test::PriorStudy later = test::writePriorStudy(source, dir + "/later", "20200101");
        QStringList files;
        for (const test::PriorStudy* s : {&older_, &newer_, &chest, &later}) {
            for (const auto& f : s->files) {
                files << QString::fromStdString(f.string());
            }
        }
        QVERIFY2(orthanc_->store(files), qPrintable(orthanc_->error()));
        chestUid_ = chest.studyUid;
    }

    void listsEveryStudyAndFetchesTheMostRecentComparable_data() {
        QTest::addColumn<bool>("dicomWeb");
        QTest::newRow("C-FIND + C-GET") << false;
        QTest::newRow("QIDO-RS + WADO-RS") << true;
    }

    void listsEveryStudyAndFetchesTheMostRecentComparable() {
        REQUIRE_DATA(kCurrent);
        QFETCH(bool, dicomWeb);
        QTemporaryDir store;
        PacsService service;
        service.setConfig(config(store.path(), dicomWeb));
        PriorsForStudy priors(service);
        QSignalSpy found(&priors, &PriorsForStudy::studiesFound);
        QSignalSpy fetches(&priors, &PriorsForStudy::fetchStarted);
        QSignalSpy ready(&priors, &PriorsForStudy::priorReady);
        QSignalSpy arrived(&service, &PacsService::seriesArrived);
        priors.start(current_, {1});
        QVERIFY(ready.wait(60000));

        // The dead node is named; the live one listed all four studies.
        QCOMPARE(priors.nodeErrors().size(), 1);
        QVERIFY(priors.nodeErrors().front().startsWith(QStringLiteral("nobody home:")));
        QCOMPARE(found.count(), 1);
        QCOMPARE(priors.studies().size(), std::size_t{4});
        QCOMPARE(priors.priorOrder(QString::fromStdString(newer_.studyUid)), 1);
        QCOMPARE(priors.priorOrder(QString::fromStdString(older_.studyUid)), 2);
        QCOMPARE(priors.priorOrder(QString::fromStdString(chestUid_)), -1); // another region
        const PatientStudy* newer = priors.study(QString::fromStdString(newer_.studyUid));
        QCOMPARE(newer->bodyParts(), std::vector<std::string>{"BRAIN"});
        QCOMPARE(newer->nodes, std::vector<int>{1});

        QCOMPARE(fetches.count(), 1);
        QCOMPARE(fetches.first().at(0).toString(), QString::fromStdString(newer_.studyUid));
        QCOMPARE(ready.first().at(0).toInt(), 1);
        QCOMPARE(ready.first().at(2).toStringList(),
                 QStringList{QString::fromStdString(newer_.seriesUid)});
        QCOMPARE(arrived.count(), 0); // a background fetch opens nothing by itself
        {
            const StudyStore s(store.path().toStdString());
            QVERIFY(s.isComplete(newer_.seriesUid));
            QCOMPARE(s.instancesOf(newer_.seriesUid).size(), newer_.files.size());
            QCOMPARE(ready.first().at(1).toString(),
                     QString::fromStdString(
                         s.seriesFolder(newer_.studyUid, newer_.seriesUid).parent_path().string()));
            QVERIFY(s.instancesOf(older_.seriesUid).empty()); // only the prior asked for
        }
        QVERIFY(priors.study(QString::fromStdString(newer_.studyUid))->completeInStore());

        // Again: it is in the store, nothing is fetched.
        fetches.clear();
        ready.clear();
        priors.start(current_, {1, 2, 3});
        QSignalSpy none(&priors, &PriorsForStudy::noPrior);
        QVERIFY(none.wait(60000));
        QCOMPARE(ready.count(), 1); // prior 1 from the store at once ...
        QCOMPARE(ready.first().at(0).toInt(), 1);
        QVERIFY(!ready.first().at(1).toString().isEmpty());
        QCOMPARE(none.first().at(0).toInt(), 3); // ... there is no third
        QVERIFY2(none.first().at(1).toString().contains(QStringLiteral("no earlier CT BRAIN")),
                 qPrintable(none.first().at(1).toString()));
        QVERIFY(ready.wait(60000)); // prior 2 is fetched
        QCOMPARE(ready.at(1).at(0).toInt(), 2);
        QCOMPARE(fetches.count(), 1);
        QCOMPARE(fetches.first().at(0).toString(), QString::fromStdString(older_.studyUid));
    }

    void aStudyOnNoNodeIsNotFetched() {
        REQUIRE_DATA(kCurrent);
        QTemporaryDir store;
        PacsService service;
        PacsConfig c = config(store.path(), false);
        c.nodes.removeLast(); // only the dead node
        service.setConfig(c);
        PriorsForStudy priors(service);
        QSignalSpy none(&priors, &PriorsForStudy::noPrior);
        priors.start(current_, {1});
        QVERIFY(none.wait(60000));
        QVERIFY2(none.first().at(1).toString().contains(QStringLiteral("nobody home")),
                 qPrintable(none.first().at(1).toString()));
        QVERIFY(!priors.fetch(QString::fromStdString(newer_.studyUid)));

        // A study without a Patient ID has no priors (an empty ID would match anyone).
        none.clear();
        CurrentStudy anonymous = current_;
        anonymous.patientId.clear();
        priors.start(anonymous, {1});
        QVERIFY(none.wait(60000));
        QVERIFY2(none.first().at(1).toString().contains(QStringLiteral("no Patient ID")),
                 qPrintable(none.first().at(1).toString()));
        QVERIFY(priors.studies().empty());
    }

private:
    PacsConfig config(const QString& store, bool dicomWeb) const {
        PacsConfig c;
        c.storeFolder = store;
        c.timeoutSeconds = 5;
        QTcpServer closed; // a port nobody listens on once this returns
        closed.listen(QHostAddress::LocalHost);
        const int deadPort = closed.serverPort();
        closed.close();
        c.nodes << PacsNodeConfig{QStringLiteral("nobody home"), QStringLiteral("NOBODY"),
                                  QStringLiteral("127.0.0.1"),   deadPort,
                                  RetrievalMethod::CGet,         {}};
        if (dicomWeb) {
            c.nodes << PacsNodeConfig{
                QStringLiteral("Orthanc web"), {}, {}, 0, RetrievalMethod::Wado,
                orthanc_->dicomWebUrl()};
        } else {
            c.nodes << PacsNodeConfig{QStringLiteral("Orthanc"),   QStringLiteral("ORTHANC"),
                                      QStringLiteral("127.0.0.1"), orthanc_->dicomPort(),
                                      RetrievalMethod::CGet,       {}};
        }
        return c;
    }

    std::unique_ptr<test::OrthancServer> orthanc_;
    QTemporaryDir made_;
    CurrentStudy current_;
    test::PriorStudy older_, newer_;
    std::string chestUid_;
};

QTEST_GUILESS_MAIN(TestPriors)
#include "test_priors.moc"
