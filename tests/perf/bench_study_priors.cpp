// Time from "open study" to the current study and its prior hung, with the prior (a
// 140-slice copy of the real CT, dated earlier) on a real Orthanc on loopback, side by
// side with the time of the same retrieval alone (SeriesRetriever into an empty store),
// by C-GET and by WADO-RS, each run on an empty store. Label perf.
#include <QApplication>
#include <QElapsedTimer>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>

#include <cstdio>

#include "core/pacs/DicomWebClient.h"
#include "core/pacs/PacsConfig.h"
#include "core/pacs/PriorsForStudy.h"
#include "core/pacs/SeriesRetriever.h"
#include "core/store/StudyStore.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/PriorStudy.h"
#include "tests/support/RealData.h"
#include "ui/app/MainWindow.h"
#include "ui/viewports/StudyHanging.h"

using namespace lucent;

namespace {

const char* kCt = "dcm_qa_ct/Philips_S21570/S2020"; // 140 x 512 x 512

} // namespace

class BenchStudyPriors : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QCoreApplication::setOrganizationName(QStringLiteral("lucent-bench"));
        QCoreApplication::setApplicationName(QStringLiteral("bench_study_priors"));
        QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, home_.path());
    }

    void openToHungAgainstRetrievalAlone() {
        REQUIRE_DATA(kCt);
        test::OrthancServer orthanc;
        QVERIFY2(orthanc.isRunning(), qPrintable("Orthanc is needed: " + orthanc.error()));
        QTemporaryDir made;
        const test::PriorStudy prior =
            test::writePriorStudy(test::kRealData / kCt, made.path().toStdString(), "20100101");
        QStringList files;
        for (const auto& f : prior.files) {
            files << QString::fromStdString(f.string());
        }
        QVERIFY2(orthanc.store(files), qPrintable(orthanc.error()));
        const PacsNodeConfig cget{QStringLiteral("Orthanc"),   QStringLiteral("ORTHANC"),
                                  QStringLiteral("127.0.0.1"), orthanc.dicomPort(),
                                  RetrievalMethod::CGet,       {}};
        const PacsNodeConfig wado{QStringLiteral("Orthanc web"), {}, {}, 0, RetrievalMethod::Wado,
                                  orthanc.dicomWebUrl()};
        std::printf("two 140-slice CTs (current from disk, prior on Orthanc), ms:\n");
        std::printf("%-8s %16s %16s %14s %14s\n", "method", "retrieval alone", "open -> hung",
                    "(listed at", "prior stored)");
        for (int round = 0; round < 2; ++round) {
            for (const PacsNodeConfig& node : {cget, wado}) {
                const qint64 alone = retrieveAlone(node, prior);
                const Hung hung = openToHung(node, prior);
                QVERIFY(alone > 0 && hung.hung > 0);
                std::printf("%-8s %16lld %16lld %14lld %14lld\n",
                            node.usesDicomWeb() ? "WADO-RS" : "C-GET",
                            static_cast<long long>(alone), static_cast<long long>(hung.hung),
                            static_cast<long long>(hung.listed),
                            static_cast<long long>(hung.stored));
            }
        }
    }

private:
    qint64 retrieveAlone(const PacsNodeConfig& node, const test::PriorStudy& prior) {
        QTemporaryDir dir;
        StudyStore store(dir.path().toStdString());
        PacsConfig config;
        QElapsedTimer clock;
        clock.start();
        const RetrieveResult r =
            node.usesDicomWeb()
                ? wadoRetrieveSeries(node.dicomWeb(), prior.studyUid, prior.seriesUid, store, {})
                : retrieveSeries(node.node(), config.dimse(), prior.studyUid, prior.seriesUid,
                                 store, {});
        const qint64 ms = clock.elapsed();
        return r.complete ? ms : -1;
    }

    struct Hung {
        qint64 hung = -1;   // open -> every viewport shows its series, the prior's too
        qint64 listed = -1; // open -> the patient's studies listed (store and PACS)
        qint64 stored = -1; // open -> the prior complete in the store
    };

    Hung openToHung(const PacsNodeConfig& node, const test::PriorStudy& prior) {
        QTemporaryDir store;
        PacsConfig config;
        config.storeFolder = store.path();
        config.nodes << node;
        {
            QSettings settings(QStringLiteral("lucent"), QStringLiteral("lucent"));
            config.save(settings);
        }
        MainWindow window;
        window.resize(1400, 900);
        window.show();
        QSignalSpy hung(window.hanging(), &StudyHanging::hung);
        QElapsedTimer clock;
        Hung times;
        connect(window.hanging()->priors(), &PriorsForStudy::studiesFound, this,
                [&] { times.listed = clock.elapsed(); });
        connect(window.hanging()->priors(), &PriorsForStudy::priorReady, this,
                [&] { times.stored = clock.elapsed(); });
        clock.start();
        window.openStudy(QString::fromStdString((test::kRealData / kCt).string()));
        if (!hung.wait(120000)) {
            return {};
        }
        times.hung = clock.elapsed();
        return StudyStore(store.path().toStdString()).isComplete(prior.seriesUid) ? times : Hung{};
    }

    QTemporaryDir home_;
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    BenchStudyPriors bench;
    return QTest::qExec(&bench, argc, argv);
}

#include "bench_study_priors.moc"
