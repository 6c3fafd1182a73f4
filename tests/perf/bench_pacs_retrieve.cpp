// Benchmark (label perf): C-GET and WADO-RS of the Philips 140-slice CT from Orthanc on
// loopback into a fresh study store, writing and indexing included. Prints the
// figures; asserts nothing about time.
#include <QTemporaryDir>
#include <QTest>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "core/pacs/DicomWebClient.h"
#include "core/pacs/DimseQuery.h"
#include "core/pacs/SeriesRetriever.h"
#include "tests/support/OrthancServer.h"

using namespace lucent;

class BenchPacsRetrieve : public QObject {
    Q_OBJECT
private slots:
    void philips140Slices() {
        const std::filesystem::path dir =
            std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2020";
        if (!std::filesystem::exists(dir)) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2020");
        }
        test::OrthancServer orthanc;
        if (!orthanc.isRunning()) {
            QSKIP(qPrintable("no test PACS: " + orthanc.error()));
        }
        QStringList files;
        for (const auto& f : std::filesystem::directory_iterator(dir)) {
            files << QString::fromStdString(f.path().string());
        }
        QVERIFY2(orthanc.store(files), qPrintable(orthanc.error()));
        const PacsNode node = PacsNode::parse(orthanc.node().toStdString());
        const PacsSettings settings;
        QueryFilter f;
        f.modalities = {"CT"};
        const auto series = find(node, settings, QueryLevel::Series, f);
        QCOMPARE(series.size(), std::size_t(1));
        // C-GET and WADO-RS alternate, so that load from other work on the
        // machine falls on both alike; each run goes into a fresh store.
        DicomWebService web;
        web.baseUrl = orthanc.dicomWebUrl().toStdString();
        auto timed = [&](auto retrieve) {
            QTemporaryDir storeDir;
            StudyStore store(storeDir.path().toStdString());
            const auto t0 = std::chrono::steady_clock::now();
            const RetrieveResult r = retrieve(store);
            const double ms =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count();
            if (r.received != 140 || !r.complete) {
                qFatal("retrieval incomplete: %d received", r.received);
            }
            return ms;
        };
        const std::string study = series[0].studyUid;
        const std::string uid = series[0].seriesUid;
        std::vector<double> cget;
        std::vector<double> wado;
        constexpr int kRuns = 5;
        for (int run = 0; run < kRuns; ++run) {
            cget.push_back(timed([&](StudyStore& store) {
                return retrieveSeries(node, settings, study, uid, store);
            }));
            wado.push_back(timed(
                [&](StudyStore& store) { return wadoRetrieveSeries(web, study, uid, store); }));
        }
        std::sort(cget.begin(), cget.end());
        std::sort(wado.begin(), wado.end());
        double load = 0;
        if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
            if (std::fscanf(f, "%lf", &load) != 1) {
                load = 0;
            }
            std::fclose(f);
        }
        qInfo("pacs_retrieve: cget_ms=%.0f wado_ms=%.0f cget_min_ms=%.0f wado_min_ms=%.0f "
              "load=%.2f (median and best of %d alternating runs, 140 instances, 74 MB, into a "
              "fresh store, writing and indexing included)",
              cget[kRuns / 2], wado[kRuns / 2], cget[0], wado[0], load, kRuns);
    }
};

QTEST_GUILESS_MAIN(BenchPacsRetrieve)
#include "bench_pacs_retrieve.moc"
