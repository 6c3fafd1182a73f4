// Benchmark (label perf): C-GET and WADO-RS of the Philips 140-slice CT from Orthanc on
// loopback into a fresh study store, writing and indexing included. Prints the
// figures; asserts nothing about time.
#include <QTemporaryDir>
#include <QTest>

#include <algorithm>
#include <chrono>
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
        std::vector<double> ms;
        for (int run = 0; run < 3; ++run) {
            QTemporaryDir storeDir;
            StudyStore store(storeDir.path().toStdString());
            const auto t0 = std::chrono::steady_clock::now();
            const RetrieveResult r =
                retrieveSeries(node, settings, series[0].studyUid, series[0].seriesUid, store);
            ms.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count());
            QCOMPARE(r.received, 140);
            QVERIFY(r.complete);
        }
        std::sort(ms.begin(), ms.end());
        DicomWebService web;
        web.baseUrl = orthanc.dicomWebUrl().toStdString();
        std::vector<double> wado;
        for (int run = 0; run < 3; ++run) {
            QTemporaryDir storeDir;
            StudyStore store(storeDir.path().toStdString());
            const auto t0 = std::chrono::steady_clock::now();
            const RetrieveResult r =
                wadoRetrieveSeries(web, series[0].studyUid, series[0].seriesUid, store);
            wado.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count());
            QCOMPARE(r.received, 140);
            QVERIFY(r.complete);
        }
        std::sort(wado.begin(), wado.end());
        qInfo("pacs_retrieve: cget_ms=%.0f wado_ms=%.0f (median of 3, 140 instances, 74 MB, into a "
              "fresh store)",
              ms[1], wado[1]);
    }
};

QTEST_GUILESS_MAIN(BenchPacsRetrieve)
#include "bench_pacs_retrieve.moc"
