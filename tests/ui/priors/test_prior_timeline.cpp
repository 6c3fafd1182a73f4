// The priors timeline on a real Orthanc: the patient's studies listed newest first with
// their prior numbers and where they are, a node that cannot be asked named; activating
// a study that is only on the PACS fetches it into the store, then opens it (the series
// to read: the CT, not the localizer). Offscreen; fails with a message without Orthanc.
#include <QApplication>
#include <QLabel>
#include <QSignalSpy>
#include <QTcpServer>
#include <QTemporaryDir>
#include <QTest>
#include <QTreeWidget>

#include <dcmtk/dcmdata/dctk.h>

#include "core/io/Catalog.h"
#include "core/pacs/PacsService.h"
#include "core/pacs/PriorsForStudy.h"
#include "core/store/StudyStore.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/PriorStudy.h"
#include "tests/support/RealData.h"
#include "ui/priors/PriorTimeline.h"

using namespace lucent;

namespace {

const char* kCurrent = "dcm_qa_ct/Philips_S21570/S2020";
const char* kPriorSource = "dcm_qa_ct/Philips_S21570/S2010";
const char* kLocalizer = "dcm_qa_ct/Philips_S21570/S1000";

QStringList filesOf(const test::PriorStudy& s) {
    QStringList files;
    for (const auto& f : s.files) {
        files << QString::fromStdString(f.string());
    }
    return files;
}

} // namespace

class TestPriorTimeline : public QObject {
    Q_OBJECT

private slots:
    void listsTheStudiesAndFetchesOneWhenActivated() {
        REQUIRE_DATA(kCurrent);
        test::OrthancServer orthanc;
        QVERIFY2(orthanc.isRunning(), qPrintable("Orthanc is needed: " + orthanc.error()));
        QTemporaryDir made;
        const std::string dir = made.path().toStdString();
        // Prior 1: a CT with its localizer (in the same study); prior 2 an older CT.
        const test::PriorStudy prior =
            test::writePriorStudy(test::kRealData / kPriorSource, dir + "/ct", "20120101");
        const test::PriorStudy older =
            test::writePriorStudy(test::kRealData / kPriorSource, dir + "/older", "20100101");
        const test::PriorStudy scout =
            test::writePriorStudy(test::kRealData / kLocalizer, dir + "/scout", "20120101");
        for (const auto& file : scout.files) { // into the prior's study
            DcmFileFormat f;
            QVERIFY(f.loadFile(file.c_str()).good());
            f.loadAllDataIntoMemory(); // written over below
            f.getDataset()->putAndInsertString(DCM_StudyInstanceUID, prior.studyUid.c_str());
            QVERIFY(f.saveFile(file.c_str(), EXS_LittleEndianExplicit).good());
        }
        const QStringList files = filesOf(prior) + filesOf(older) + filesOf(scout);
        QVERIFY2(orthanc.store(files), qPrintable(orthanc.error()));

        QTemporaryDir store;
        PacsConfig config;
        config.storeFolder = store.path();
        config.timeoutSeconds = 5;
        QTcpServer closed;
        closed.listen(QHostAddress::LocalHost);
        const int deadPort = closed.serverPort();
        closed.close();
        config.nodes << PacsNodeConfig{QStringLiteral("Orthanc"),   QStringLiteral("ORTHANC"),
                                       QStringLiteral("127.0.0.1"), orthanc.dicomPort(),
                                       RetrievalMethod::CGet,       {}}
                     << PacsNodeConfig{QStringLiteral("Offline"),   QStringLiteral("OFFLINE"),
                                       QStringLiteral("127.0.0.1"), deadPort,
                                       RetrievalMethod::CGet,       {}};
        PacsService service;
        service.setConfig(config);
        PriorsForStudy priors(service);
        PriorTimeline timeline(priors);
        timeline.resize(700, 300);
        timeline.show();

        const SeriesEntry e = scanPath((test::kRealData / kCurrent).string()).series.front();
        QSignalSpy found(&priors, &PriorsForStudy::studiesFound);
        priors.start({e.patientId, e.studyUid, e.modality, e.bodyPart, e.studyDate, e.studyTime},
                     {});
        QVERIFY(found.wait(30000));
        QTreeWidget* list = timeline.list();
        QCOMPARE(list->topLevelItemCount(), 2);
        QTreeWidgetItem* first = list->topLevelItem(0);
        QCOMPARE(first->text(0), QStringLiteral("2012-01-01"));
        QCOMPARE(first->text(1), QStringLiteral("prior 1"));
        QCOMPARE(first->text(3), QStringLiteral("Orthanc"));
        QCOMPARE(first->text(4), QStringLiteral("on PACS"));
        QCOMPARE(list->topLevelItem(1)->text(1), QStringLiteral("prior 2"));
        const QLabel* heading = timeline.findChild<QLabel*>();
        QVERIFY2(heading->text().contains(QStringLiteral("Offline:")), qPrintable(heading->text()));

        // Nothing was fetched by the lookup alone.
        QVERIFY(StudyStore(store.path().toStdString()).instancesOf(prior.seriesUid).empty());

        QSignalSpy opened(&timeline, &PriorTimeline::openStudy);
        QSignalSpy fetches(&priors, &PriorsForStudy::fetchStarted);
        emit list->itemActivated(first, 0);
        QVERIFY(opened.wait(60000));
        QCOMPARE(fetches.count(), 1);
        QCOMPARE(opened.first().at(1).toString(), QString::fromStdString(prior.seriesUid));
        const QString folder = opened.first().at(0).toString();
        const Catalog there = scanPath(folder.toStdString());
        QCOMPARE(there.series.size(), std::size_t{2}); // the whole study: CT and localizer
        QVERIFY(StudyStore(store.path().toStdString()).isComplete(scout.seriesUid));
        first = list->topLevelItem(0);
        QCOMPARE(first->text(3), QStringLiteral("store, Orthanc"));
        QCOMPARE(first->text(4), QStringLiteral("in the store"));

        // Activated again: opened from the store, nothing fetched.
        opened.clear();
        emit list->itemActivated(first, 0);
        QCOMPARE(opened.count(), 1);
        QCOMPARE(fetches.count(), 1);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestPriorTimeline test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_prior_timeline.moc"
