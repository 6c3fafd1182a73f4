// The PACS widgets driven as a user would, against a real Orthanc on loopback:
// node settings with Echo, date presets, query into the study -> series tree,
// retrieve with per-series progress ending in the store and the open signal,
// cancel. Labels ui and pacs; offscreen Qt platform.
#include <QApplication>
#include <QComboBox>
#include <QDateEdit>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTest>
#include <QTreeWidget>

#include <filesystem>
#include <memory>

#include "core/pacs/PacsService.h"
#include "core/store/StudyStore.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/SyntheticDicom.h"
#include "ui/pacs/PacsBrowser.h"
#include "ui/pacs/PacsNodeSettings.h"
#include "ui/pacs/PacsQueryPanel.h"
#include "ui/pacs/RetrievalProgress.h"
#include "ui/pacs/StoreBrowser.h"

using namespace lucent;

namespace {
const char* kStudy = "1.2.826.0.1.3680043.2.1125.971";
const char* kSeriesCt = "1.2.826.0.1.3680043.2.1125.9711";
const char* kSeriesMr = "1.2.826.0.1.3680043.2.1125.9712";
const char* kBigStudy = "1.2.826.0.1.3680043.2.1125.972";
constexpr int kBigImages = 120;

template <class T> T* child(QWidget* parent, const char* name) {
    T* w = parent->findChild<T*>(QString::fromLatin1(name));
    if (w == nullptr) {
        qFatal("no widget named %s", name);
    }
    return w;
}
} // namespace

class TestPacsUi : public QObject {
    Q_OBJECT
    std::unique_ptr<test::OrthancServer> orthanc_;
    QTemporaryDir files_;
    QTemporaryDir home_; // settings file and store
    int scpPort_ = 0;
    std::unique_ptr<PacsBrowser> browser_;

    QString storeFolder() const { return home_.filePath("store"); }

    void write(test::SyntheticSeries s, int images, QStringList& files) {
        std::vector<glm::dvec3> positions;
        for (int k = 0; k < images; ++k) {
            positions.emplace_back(0.0, 0.0, 1.0 * k);
        }
        const std::string dir = files_.filePath(QString::fromStdString(s.seriesUid)).toStdString();
        std::filesystem::create_directories(dir);
        for (const std::string& f : test::writeSeries(dir, s, positions)) {
            files << QString::fromStdString(f);
        }
    }

    // Searches by patient name on the node at index `node`; waits for the tree.
    void search(int node, const QString& patientName) {
        PacsQueryPanel* q = browser_->queryPanel();
        child<QComboBox>(q, "node")->setCurrentIndex(node);
        child<QLineEdit>(q, "patientName")->setText(patientName);
        QSignalSpy done(browser_->service(), &PacsService::queryFinished);
        QTest::mouseClick(child<QPushButton>(q, "search"), Qt::LeftButton);
        QVERIFY2(done.wait(30000), qPrintable(q->status()->text()));
    }

private slots:
    void initTestCase() {
        scpPort_ = test::OrthancServer::freePort();
        orthanc_ = std::make_unique<test::OrthancServer>(scpPort_);
        if (!orthanc_->isRunning()) {
            QSKIP(qPrintable("no test PACS: " + orthanc_->error()));
        }
        QStringList files;
        test::SyntheticSeries s;
        s.patientName = "Tree^Tom";
        s.patientId = "T001";
        s.studyDate = QDate::currentDate().addDays(-3).toString("yyyyMMdd").toStdString();
        s.accessionNumber = "TREE1";
        s.studyUid = kStudy;
        s.seriesUid = kSeriesCt;
        s.seriesNumber = 1;
        write(s, 4, files);
        s.seriesUid = kSeriesMr;
        s.modality = "MR";
        s.seriesNumber = 2;
        write(s, 3, files);
        test::SyntheticSeries big;
        big.patientName = "Big^Bertha";
        big.patientId = "B001";
        big.studyUid = kBigStudy;
        big.columns = 256;
        big.rows = 256;
        for (const char* series :
             {"1.2.826.0.1.3680043.2.1125.9721", "1.2.826.0.1.3680043.2.1125.9722"}) {
            big.seriesUid = series;
            ++big.seriesNumber;
            write(big, kBigImages, files);
        }
        QVERIFY2(orthanc_->store(files), qPrintable(orthanc_->error()));

        // The settings a user would have saved: one node per retrieval method.
        QSettings ini(home_.filePath("lucent.ini"), QSettings::IniFormat);
        PacsConfig config;
        config.storeFolder = storeFolder();
        config.storagePort = scpPort_;
        config.timeoutSeconds = 10;
        const QString host = "127.0.0.1";
        config.nodes << PacsNodeConfig{
            "Orthanc C-GET", "ORTHANC", host, orthanc_->dicomPort(), RetrievalMethod::CGet, {}};
        config.nodes << PacsNodeConfig{
            "Orthanc C-MOVE", "ORTHANC", host, orthanc_->dicomPort(), RetrievalMethod::CMove, {}};
        config.nodes << PacsNodeConfig{"Orthanc web",          {}, {}, 104, RetrievalMethod::Wado,
                                       orthanc_->dicomWebUrl()};
        config.save(ini);
        browser_ = std::make_unique<PacsBrowser>(home_.filePath("lucent.ini"));
        browser_->resize(900, 700);
        browser_->show();
        QCOMPARE(browser_->config().nodes.size(), 3);
    }
    void cleanupTestCase() {
        browser_.reset();
        orthanc_.reset();
    }

    void echoButtonShowsTheResult() {
        PacsNodeSettings* dialog = browser_->showNodeSettings();
        auto* nodes = child<QListWidget>(dialog, "nodes");
        QCOMPARE(nodes->count(), 3);
        QPushButton* echo = child<QPushButton>(dialog, "echo");
        for (int row : {0, 2}) { // C-ECHO, and a DICOMweb request for the web node
            nodes->setCurrentRow(row);
            QTest::mouseClick(echo, Qt::LeftButton);
            QTRY_VERIFY_WITH_TIMEOUT(echo->isEnabled(), 15000);
            QVERIFY2(dialog->echoResult()->text().startsWith("OK"),
                     qPrintable(dialog->echoResult()->text()));
        }
        nodes->setCurrentRow(0);
        child<QSpinBox>(dialog, "port")->setValue(test::OrthancServer::freePort());
        QTest::mouseClick(echo, Qt::LeftButton);
        QTRY_VERIFY_WITH_TIMEOUT(echo->isEnabled(), 15000);
        QVERIFY2(dialog->echoResult()->text().contains("connection refused"),
                 qPrintable(dialog->echoResult()->text()));
        // Bad input names the field, and nothing is saved.
        child<QLineEdit>(dialog, "aeTitle")->setText("MUCH_TOO_LONG_AE_TITLE");
        QTest::mouseClick(echo, Qt::LeftButton);
        QVERIFY2(dialog->echoResult()->text().contains("AE title"),
                 qPrintable(dialog->echoResult()->text()));
        QVERIFY(!dialog->save());
        QVERIFY2(dialog->error()->text().contains("AE title"), qPrintable(dialog->error()->text()));
        child<QLineEdit>(dialog, "aeTitle")->setText("ORTHANC");
        child<QSpinBox>(dialog, "port")->setValue(orthanc_->dicomPort());
        child<QLineEdit>(dialog, "host")->clear();
        QVERIFY(!dialog->save());
        QVERIFY2(dialog->error()->text().contains("Host"), qPrintable(dialog->error()->text()));
        child<QLineEdit>(dialog, "host")->setText("127.0.0.1");
        child<QLineEdit>(dialog, "name")->setText("Orthanc here");
        QVERIFY2(dialog->save(), qPrintable(dialog->error()->text()));
        QSettings ini(home_.filePath("lucent.ini"), QSettings::IniFormat);
        const PacsConfig saved = PacsConfig::load(ini);
        QCOMPARE(saved.nodes.size(), 3);
        QCOMPARE(saved.nodes[0].name, QString("Orthanc here"));
        QCOMPARE(saved.nodes[0].port, orthanc_->dicomPort());
        QCOMPARE(saved.nodes[2].method, RetrievalMethod::Wado);
        QCOMPARE(child<QComboBox>(browser_->queryPanel(), "node")->itemText(0),
                 QString("Orthanc here"));
        dialog->close();
    }

    void datePresetsSetTheRange() {
        PacsQueryPanel* q = browser_->queryPanel();
        auto* preset = child<QComboBox>(q, "datePreset");
        const QDate today = QDate::currentDate();
        auto range = [&](int index) {
            preset->setCurrentIndex(index);
            emit preset->activated(index); // what choosing it with the mouse does
            QString error;
            const QueryFilter f = q->filter(&error);
            return QString::fromStdString(f.dateRange);
        };
        auto d = [](QDate x) { return x.toString("yyyyMMdd"); };
        QCOMPARE(range(1), d(today) + "-" + d(today));
        QCOMPARE(range(2), d(today.addDays(-6)) + "-" + d(today));
        QCOMPARE(range(3), d(today.addMonths(-1)) + "-" + d(today));
        QCOMPARE(child<QDateEdit>(q, "dateFrom")->date(), today.addMonths(-1));
        QCOMPARE(range(0), QString());
        QVERIFY(!child<QDateEdit>(q, "dateFrom")->isEnabled());
    }

    void queryFillsTheStudySeriesTree() {
        PacsQueryPanel* q = browser_->queryPanel();
        QTreeWidget* tree = q->results();
        for (int node : {0, 2}) { // C-FIND and QIDO-RS
            child<QComboBox>(q, "datePreset")->setCurrentIndex(2);
            emit child<QComboBox>(q, "datePreset")->activated(2); // last 7 days: Tom's study
            search(node, "Tree*");
            QCOMPARE(tree->topLevelItemCount(), 1);
            QTreeWidgetItem* study = tree->topLevelItem(0);
            QCOMPARE(study->text(PacsQueryPanel::Name), QString("Tree^Tom"));
            QCOMPARE(study->data(PacsQueryPanel::Name, PacsQueryPanel::kUidRole).toString(),
                     QString(kStudy));
            QCOMPARE(study->childCount(), 2);
            QCOMPARE(study->child(0)->text(PacsQueryPanel::Modality), QString("CT"));
            QCOMPARE(study->child(0)->text(PacsQueryPanel::Instances), QString("4"));
            QCOMPARE(study->child(1)->text(PacsQueryPanel::Modality), QString("MR"));
        }
        child<QLineEdit>(q, "modalities")->setText("mr");
        search(0, "Tree*");
        QCOMPARE(tree->topLevelItemCount(), 1);
        QCOMPARE(tree->topLevelItem(0)->childCount(), 1);
        child<QLineEdit>(q, "modalities")->clear();
        // Out of the date range: nothing.
        child<QComboBox>(q, "datePreset")->setCurrentIndex(1);
        emit child<QComboBox>(q, "datePreset")->activated(1);
        search(0, "Tree*");
        QCOMPARE(tree->topLevelItemCount(), 0);
        // Bad input names the field.
        child<QLineEdit>(q, "modalities")->setText("C T!");
        QTest::mouseClick(child<QPushButton>(q, "search"), Qt::LeftButton);
        QVERIFY2(q->status()->text().contains("Modalities"), qPrintable(q->status()->text()));
        child<QLineEdit>(q, "modalities")->clear();
        child<QComboBox>(q, "datePreset")->setCurrentIndex(0);
        emit child<QComboBox>(q, "datePreset")->activated(0);
    }

    void retrieveShowsProgressStoresAndOpens() {
        for (int node : {0, 1, 2}) { // C-GET, C-MOVE, WADO-RS, each into a fresh store
            PacsConfig config = browser_->config();
            config.storeFolder = storeFolder() + QString::number(node);
            browser_->setConfig(config);
            search(node, "Tree*");
            QTreeWidget* tree = browser_->queryPanel()->results();
            tree->topLevelItem(0)->setSelected(true); // the study: both series
            QSignalSpy opened(browser_.get(), &PacsBrowser::openSeries);
            QSignalSpy done(browser_->service(), &PacsService::allRetrievalsFinished);
            QTest::mouseClick(child<QPushButton>(browser_->queryPanel(), "retrieve"),
                              Qt::LeftButton);
            QVERIFY(done.wait(60000));
            RetrievalProgress* p = browser_->progress();
            for (const auto& [uid, count] : {std::pair{kSeriesCt, 4}, std::pair{kSeriesMr, 3}}) {
                QTreeWidgetItem* row = p->row(uid);
                QVERIFY(row != nullptr);
                QVERIFY2(row->text(RetrievalProgress::Status).startsWith("complete"),
                         qPrintable(row->text(RetrievalProgress::Status)));
                QCOMPARE(row->text(RetrievalProgress::Completed), QString::number(count));
                QCOMPARE(row->text(RetrievalProgress::Remaining), QString("0"));
                QCOMPARE(row->text(RetrievalProgress::Failed), QString("0"));
            }
            QCOMPARE(opened.size(), 2);
            const QString folder = opened[0][0].toString();
            QCOMPARE(opened[0][1].toString(), QString(kSeriesCt));
            StudyStore store(config.storeFolder.toStdString());
            QVERIFY(store.isComplete(kSeriesCt) && store.isComplete(kSeriesMr));
            QCOMPARE(folder.toStdString(), store.seriesFolder(kStudy, kSeriesCt).string());
            // The local store tab reads the index.
            QTreeWidget* local = browser_->store()->tree();
            QCOMPARE(local->topLevelItemCount(), 1);
            QTreeWidgetItem* series = local->topLevelItem(0)->child(0)->child(0);
            QCOMPARE(series->text(4), QString("complete"));
            QCOMPARE(series->data(0, StoreBrowser::kSeriesUidRole).toString(), QString(kSeriesCt));
        }
    }

    void cancelStopsTheRetrievals() {
        PacsConfig config = browser_->config();
        config.storeFolder = storeFolder() + "-cancel";
        browser_->setConfig(config);
        search(0, "Big*");
        QTreeWidget* tree = browser_->queryPanel()->results();
        QCOMPARE(tree->topLevelItemCount(), 1);
        tree->topLevelItem(0)->setSelected(true); // two series, the second queued
        QPushButton* cancel = child<QPushButton>(browser_->progress(), "cancelRetrievals");
        connect(browser_->service(), &PacsService::retrievalProgress, cancel,
                [cancel](const QString&, int completed) {
                    if (completed >= 2 && cancel->isEnabled()) {
                        QTest::mouseClick(cancel, Qt::LeftButton);
                    }
                });
        QSignalSpy done(browser_->service(), &PacsService::allRetrievalsFinished);
        QTest::mouseClick(child<QPushButton>(browser_->queryPanel(), "retrieve"), Qt::LeftButton);
        QVERIFY(done.wait(60000));
        for (const char* uid :
             {"1.2.826.0.1.3680043.2.1125.9721", "1.2.826.0.1.3680043.2.1125.9722"}) {
            QTreeWidgetItem* row = browser_->progress()->row(uid);
            QVERIFY(row != nullptr);
            QVERIFY2(row->text(RetrievalProgress::Status).contains("cancelled"),
                     qPrintable(row->text(RetrievalProgress::Status)));
        }
        StudyStore store(config.storeFolder.toStdString());
        const std::size_t first = store.instancesOf("1.2.826.0.1.3680043.2.1125.9721").size();
        QVERIFY2(first >= 2 && first < kBigImages, qPrintable(QString::number(first)));
        qInfo("cancelled after %zu of %d instances", first, kBigImages);
        QVERIFY(store.instancesOf("1.2.826.0.1.3680043.2.1125.9722").empty());
        QVERIFY(!cancel->isEnabled());
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestPacsUi test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_pacs_ui.moc"
