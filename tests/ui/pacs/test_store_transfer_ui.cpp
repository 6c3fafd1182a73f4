// The local store's context menu driven as a user would: a real CT series
// retrieved into the store is sent to a second Orthanc (C-STORE and STOW-RS,
// each instance's status in the transfers list, a dead node named), and
// exported de-identified to a ZIP with a DICOMDIR through the export dialog.
// Labels ui and pacs; offscreen Qt platform.
#include <QApplication>
#include <QCheckBox>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QTreeWidget>

#include <filesystem>
#include <memory>

#include "core/exchange/InstanceFiles.h"
#include "core/pacs/DimseQuery.h"
#include "core/pacs/PacsService.h"
#include "core/pacs/SeriesRetriever.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/OrthancServer.h"
#include "ui/pacs/ExportDialog.h"
#include "ui/pacs/PacsBrowser.h"
#include "ui/pacs/RetrievalProgress.h"
#include "ui/pacs/StoreBrowser.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {
const fs::path kData = LUCENT_TEST_DATA_DIR;
const char* kCtFiles[] = {"01.dcm", "02.dcm", "03.dcm"};

// Instances of the series that a node holds, by C-FIND.
int instancesOn(const test::OrthancServer& o, const InstanceHeader& of) {
    QueryFilter f;
    f.studyUid = of.studyUid;
    for (const QueryMatch& m :
         find(PacsNode::parse(o.node().toStdString()), {}, QueryLevel::Series, f)) {
        if (m.seriesUid == of.seriesUid) {
            return m.instances;
        }
    }
    return 0;
}
} // namespace

class TestStoreTransferUi : public QObject {
    Q_OBJECT
    std::unique_ptr<test::OrthancServer> source_, target_;
    QTemporaryDir home_;
    std::unique_ptr<PacsBrowser> browser_;
    InstanceHeader ct_;

    QTreeWidgetItem* storedSeries() const {
        QTreeWidget* tree = browser_->store()->tree();
        return tree->topLevelItemCount() == 0 ? nullptr : tree->topLevelItem(0)->child(0)->child(0);
    }
    // Triggers an action of the store's context menu on `item`, as a click would.
    void trigger(QTreeWidgetItem* item, const char* action) {
        QMenu menu;
        browser_->store()->fillContextMenu(menu, item);
        QAction* a = menu.findChild<QAction*>(QString::fromLatin1(action));
        QVERIFY2(a != nullptr && a->isEnabled(), action);
        a->trigger();
    }
    QTreeWidgetItem* sendAndWait(int node) {
        QSignalSpy done(browser_->service(), &PacsService::allRetrievalsFinished);
        trigger(storedSeries()->parent(), qPrintable(QString("sendTo%1").arg(node))); // the study
        [&] { QVERIFY(done.wait(60000)); }();
        RetrievalProgress* p = browser_->progress();
        return p->list()->topLevelItem(p->list()->topLevelItemCount() - 1);
    }

private slots:
    void initTestCase() {
        if (!fs::exists(kData / "dcmqi_ct3slice")) {
            QSKIP("real test data not found: ../shared/data/dcmqi_ct3slice");
        }
        source_ = std::make_unique<test::OrthancServer>();
        target_ = std::make_unique<test::OrthancServer>();
        QVERIFY2(source_->isRunning(), qPrintable("no test PACS: " + source_->error()));
        QVERIFY2(target_->isRunning(), qPrintable("no test PACS: " + target_->error()));
        QStringList files;
        for (const char* f : kCtFiles) {
            files << QString::fromStdString((kData / "dcmqi_ct3slice" / f).string());
        }
        QVERIFY2(source_->store(files), qPrintable(source_->error()));
        ct_ = readInstanceHeader(files[0].toStdString());
        // The store holds the series as a retrieval left it.
        {
            StudyStore store(home_.filePath("store").toStdString());
            const RetrieveResult r = retrieveSeries(PacsNode::parse(source_->node().toStdString()),
                                                    {}, ct_.studyUid, ct_.seriesUid, store);
            QVERIFY(r.complete);
        }
        QSettings ini(home_.filePath("lucent.ini"), QSettings::IniFormat);
        PacsConfig config;
        config.storeFolder = home_.filePath("store");
        config.timeoutSeconds = 10;
        const QString host = "127.0.0.1";
        config.nodes << PacsNodeConfig{
            "Target", "ORTHANC", host, target_->dicomPort(), RetrievalMethod::CGet, {}};
        config.nodes << PacsNodeConfig{"Target web",          {}, {}, 104, RetrievalMethod::Wado,
                                       target_->dicomWebUrl()};
        config.nodes << PacsNodeConfig{
            "Nobody", "NOBODY", host, test::OrthancServer::freePort(), RetrievalMethod::CGet, {}};
        config.save(ini);
        browser_ = std::make_unique<PacsBrowser>(home_.filePath("lucent.ini"));
        browser_->resize(900, 700);
        browser_->show();
        QVERIFY(storedSeries() != nullptr);
    }
    void cleanupTestCase() {
        browser_.reset();
        source_.reset();
        target_.reset();
    }

    void sendByCStoreShowsEachInstance() {
        QCOMPARE(instancesOn(*target_, ct_), 0);
        QTreeWidgetItem* row = sendAndWait(0);
        QVERIFY2(row->text(RetrievalProgress::Status).startsWith("sent: 3 stored"),
                 qPrintable(row->text(RetrievalProgress::Status)));
        QCOMPARE(row->text(RetrievalProgress::Completed), QString("3"));
        QCOMPARE(row->childCount(), 0);
        QCOMPARE(instancesOn(*target_, ct_), 3);
    }

    void sendByStowShowsEachInstance() {
        QTreeWidgetItem* row = sendAndWait(1);
        QVERIFY2(row->text(RetrievalProgress::Status).startsWith("sent: 3 stored"),
                 qPrintable(row->text(RetrievalProgress::Status)));
        QCOMPARE(instancesOn(*target_, ct_), 3);
    }

    void deadNodeIsNamed() {
        QTreeWidgetItem* row = sendAndWait(2);
        const QString status = row->text(RetrievalProgress::Status);
        QVERIFY2(status.contains("NOBODY@127.0.0.1") && status.contains("refused"),
                 qPrintable(status));
    }

    void exportDialogWritesADeidentifiedZip() {
        trigger(storedSeries(), "export");
        ExportDialog* dialog = browser_->findChild<ExportDialog*>();
        QVERIFY(dialog != nullptr && dialog->isVisible());
        const QString zip = home_.filePath("teaching.zip");
        dialog->output()->setText(zip);
        dialog->anonymize()->setChecked(true);
        dialog->dicomdir()->setChecked(true);
        QSignalSpy finished(dialog, &ExportDialog::exportFinished);
        QTest::mouseClick(dialog->exportButton(), Qt::LeftButton);
        QVERIFY(finished.wait(60000));
        QVERIFY2(finished[0][0].toBool(), qPrintable(dialog->status()->text()));
        QVERIFY(dialog->status()->text().contains("3 instance(s) exported, de-identified,"));
        QVERIFY(fs::file_size(zip.toStdString()) > 100000);
        // Again to the same name: refused, said in the dialog, the ZIP kept.
        const auto size = fs::file_size(zip.toStdString());
        QTest::mouseClick(dialog->exportButton(), Qt::LeftButton);
        QVERIFY(finished.wait(60000));
        QVERIFY(!finished[1][0].toBool());
        QVERIFY2(dialog->status()->text().contains("exists already"),
                 qPrintable(dialog->status()->text()));
        QCOMPARE(fs::file_size(zip.toStdString()), size);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestStoreTransferUi test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_store_transfer_ui.moc"
