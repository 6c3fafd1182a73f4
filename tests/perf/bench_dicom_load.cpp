// Benchmark (label perf): scan + load of the Philips 140-slice CT with a warm
// page cache, inside the process, all geometry checks on. Prints the figures;
// asserts nothing about time (timing belongs to benchmarks, not tests).
#include <QTest>

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "core/io/Catalog.h"

using namespace lucent;

class BenchDicomLoad : public QObject {
    Q_OBJECT
private slots:
    void philips140Slices() {
        const std::filesystem::path dir =
            std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2020";
        if (!std::filesystem::exists(dir)) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2020");
        }
        using Clock = std::chrono::steady_clock;
        const auto ms = [](Clock::duration d) {
            return std::chrono::duration<double, std::milli>(d).count();
        };
        loadPath(dir); // warm the page cache
        std::vector<double> total, scan, decode;
        for (int run = 0; run < 10; ++run) {
            const auto t0 = Clock::now();
            const Catalog catalog = scanPath(dir);
            const auto t1 = Clock::now();
            const Volume v = loadSeries(*catalog.defaultEntry());
            const auto t2 = Clock::now();
            QCOMPARE(v.dims(), glm::ivec3(512, 512, 140));
            scan.push_back(ms(t1 - t0));
            decode.push_back(ms(t2 - t1));
            total.push_back(ms(t2 - t0));
        }
        const auto median = [](std::vector<double> v) {
            std::sort(v.begin(), v.end());
            return 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
        };
        qInfo("philips_140: load_ms=%.1f scan_ms=%.1f decode_ms=%.1f (median of 10, warm cache)",
              median(total), median(scan), median(decode));
    }
};

QTEST_APPLESS_MAIN(BenchDicomLoad)
#include "bench_dicom_load.moc"
