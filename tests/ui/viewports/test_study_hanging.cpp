// A follow-up read with no setup: opening the current study (a real CT) hangs it with the
// best protocol, finds the patient's prior on a real Orthanc by itself, fetches it into
// the store and hangs both; a second open fetches nothing. Prints the time from "open
// study" to both hung. Offscreen; fails with a message when Orthanc is missing.
#include <QApplication>
#include <QElapsedTimer>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>

#include <cstdio>
#include <set>

#include "core/pacs/PacsConfig.h"
#include "core/pacs/PacsService.h"
#include "core/pacs/PriorsForStudy.h"
#include "core/store/StudyStore.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/PriorStudy.h"
#include "tests/support/RealData.h"
#include "ui/app/MainWindow.h"
#include "ui/mpr/MprCursor.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/StudyHanging.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportLinks.h"
#include "ui/viewports/ViewportRegistration.h"
#include "ui/viewports/ViewportWorkspace.h"

using namespace lucent;

namespace {

const char* kCurrent = "dcm_qa_ct/Philips_S21570/S2020"; // 140 x 1 mm, the study read today
const char* kPriorSource = "dcm_qa_ct/Philips_S21570/S2010";

std::set<std::string> studiesShown(const ViewportWorkspace& workspace) {
    std::set<std::string> studies;
    for (const Viewport* v : workspace.grid()->viewports()) {
        if (v->session() != nullptr) {
            studies.insert(v->session()->info().studyUid);
        }
    }
    return studies;
}

QStringList filesOf(const test::PriorStudy& study) {
    QStringList files;
    for (const auto& f : study.files) {
        files << QString::fromStdString(f.string());
    }
    return files;
}

// The settings MainWindow reads: the store and Orthanc as the one PACS node (C-GET).
PacsConfig useOrthanc(const test::OrthancServer& orthanc, int scpPort, const QString& store) {
    PacsConfig config;
    config.storeFolder = store;
    config.storagePort = scpPort;
    config.timeoutSeconds = 10;
    config.nodes << PacsNodeConfig{QStringLiteral("Orthanc"),   QStringLiteral("ORTHANC"),
                                   QStringLiteral("127.0.0.1"), orthanc.dicomPort(),
                                   RetrievalMethod::CGet,       {}};
    QSettings settings(QStringLiteral("lucent"), QStringLiteral("lucent"));
    config.save(settings);
    return config;
}

} // namespace

class TestStudyHanging : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QCoreApplication::setOrganizationName(QStringLiteral("lucent-test"));
        QCoreApplication::setApplicationName(QStringLiteral("test_study_hanging"));
        QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, home_.path());
    }

    void priorFetchedByItselfAndHungBesideTheCurrentStudy() {
        REQUIRE_DATA(kCurrent);
        const int scpPort = test::OrthancServer::freePort();
        test::OrthancServer orthanc(scpPort);
        QVERIFY2(orthanc.isRunning(), qPrintable("Orthanc is needed: " + orthanc.error()));
        // Last year's CT of the same patient, on the PACS only (same Frame of Reference).
        const test::PriorStudy prior = test::writePriorStudy(
            test::kRealData / kPriorSource, priorDir_.path().toStdString(), "20100101");
        QVERIFY2(orthanc.store(filesOf(prior)), qPrintable(orthanc.error()));
        const PacsConfig config =
            useOrthanc(orthanc, scpPort, home_.filePath(QStringLiteral("store")));

        MainWindow window;
        window.resize(1400, 900);
        window.show();
        StudyHanging* hanging = window.hanging();
        QVERIFY(hanging->priors() != nullptr);
        QSignalSpy hung(hanging, &StudyHanging::hung);
        QSignalSpy retrievals(hanging->priors(), &PriorsForStudy::fetchStarted);
        const QString current = QString::fromStdString((test::kRealData / kCurrent).string());
        QElapsedTimer clock;
        clock.start();
        window.openStudy(current);
        QVERIFY(hung.wait(120000));
        const qint64 firstMs = clock.elapsed();
        std::printf("open study -> current and prior hung: %lld ms (protocol %s)\n",
                    static_cast<long long>(firstMs), qPrintable(hung.first().at(0).toString()));
        QVERIFY(window.workspaceShown());
        QCOMPARE(retrievals.count(), 1);

        // Both studies hang, the prior from the store where it was fetched.
        const std::set<std::string> studies = studiesShown(*window.workspace());
        QVERIFY2(studies.count(prior.studyUid) == 1, "the prior is not in any viewport");
        QCOMPARE(studies.size(), std::size_t{2});
        {
            const StudyStore store(config.storeFolder.toStdString());
            QVERIFY(store.isComplete(prior.seriesUid));
            QCOMPARE(static_cast<int>(store.instancesOf(prior.seriesUid).size()),
                     static_cast<int>(prior.files.size()));
        }
        const HangingResult* applied = hanging->applied();
        QVERIFY(applied != nullptr);
        QVERIFY(applied->missingStudyOrders.empty());

        // The same Frame of Reference: scrolling the current study moves the prior by
        // itself (its viewports are linked by the protocol).
        Viewport* currentView = nullptr;
        Viewport* priorView = nullptr;
        for (Viewport* v : window.workspace()->grid()->viewports()) {
            if (v->session() == nullptr || v->sliceView() == nullptr || v->linkGroup() == 0) {
                continue;
            }
            (v->session()->info().studyUid == prior.studyUid ? priorView : currentView) = v;
        }
        QVERIFY(currentView != nullptr && priorView != nullptr);
        QCOMPARE(currentView->linkGroup(), priorView->linkGroup());
        const glm::dvec3 moved = currentView->session()->cursor()->point() + glm::dvec3(0, 0, 20);
        currentView->session()->cursor()->setPoint(moved);
        QVERIFY(std::abs(priorView->session()->cursor()->point().z - moved.z) <=
                priorView->session()->volume()->geometry().spacing.z / 2 + 1e-3);

        // A second open fetches nothing: the prior is in the store.
        hung.clear();
        retrievals.clear();
        clock.restart();
        window.openStudy(current);
        QVERIFY(hung.wait(120000));
        std::printf("second open (prior in the store): %lld ms\n",
                    static_cast<long long>(clock.elapsed()));
        QCOMPARE(retrievals.count(), 0);
        QCOMPARE(studiesShown(*window.workspace()).size(), std::size_t{2});
    }

    // A prior from another scanner (its own Frame of Reference, the anatomy 9 mm away):
    // hung beside the current study, then registered by itself; scrolling lands on the
    // same anatomy through the registration.
    void priorOfAnotherScannerRegisteredByItself() {
        REQUIRE_DATA(kCurrent);
        const int scpPort = test::OrthancServer::freePort();
        test::OrthancServer orthanc(scpPort);
        QVERIFY2(orthanc.isRunning(), qPrintable("Orthanc is needed: " + orthanc.error()));
        QTemporaryDir made;
        const glm::dvec3 shift(6.0, -4.5, 9.0);
        const test::PriorStudy prior = test::writePriorStudy(
            test::kRealData / kPriorSource, made.path().toStdString(), "20100101", shift);
        QVERIFY2(orthanc.store(filesOf(prior)), qPrintable(orthanc.error()));
        QTemporaryDir store;
        useOrthanc(orthanc, scpPort, store.path());
        MainWindow window;
        window.resize(1400, 900);
        window.show();
        QSignalSpy registered(window.workspace()->registration(), &ViewportRegistration::finished);
        window.openStudy(QString::fromStdString((test::kRealData / kCurrent).string()));
        QVERIFY(registered.wait(180000));
        QVERIFY2(registered.first().at(0).toBool(),
                 qPrintable(registered.first().at(1).toString()));

        Viewport* currentView = nullptr;
        Viewport* priorView = nullptr;
        for (Viewport* v : window.workspace()->grid()->viewports()) {
            if (v->session() != nullptr && v->sliceView() != nullptr && v->linkGroup() != 0) {
                (v->session()->info().studyUid == prior.studyUid ? priorView : currentView) = v;
            }
        }
        QVERIFY(currentView != nullptr && priorView != nullptr);
        QVERIFY(window.workspace()
                    ->links()
                    ->linkBetween(*currentView->session(), *priorView->session())
                    .kind == SeriesLink::Kind::Registered);
        const glm::dvec3 moved = currentView->session()->cursor()->point() + glm::dvec3(0, 0, 15);
        currentView->session()->cursor()->setPoint(moved);
        // Within half a prior slice, plus the half millimetre registration may be off by.
        QVERIFY(std::abs(priorView->session()->cursor()->point().z - (moved.z + shift.z)) <=
                priorView->session()->volume()->geometry().spacing.z / 2 + 0.5);
    }

private:
    QTemporaryDir home_;
    QTemporaryDir priorDir_;
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestStudyHanging test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_study_hanging.moc"
