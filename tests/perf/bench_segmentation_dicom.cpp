// Benchmark (label perf): DICOM SEG write and read of ten segments on the real 140-slice CT
// (512x512), warm page cache, median of 5; with node and dcmjs (OHIF's DICOM library,
// tests/segdicom/dcmjs) the same masks written by dcmjs side by side. Prints the figures;
// asserts nothing about time, only that what was read is what was written.
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <algorithm>
#include <chrono>
#include <fstream>

#include "core/segdicom/SegmentationDicom.h"
#include "tests/core/segdicom/SegmentedCt.h"
#include "tests/segdicom/DcmjsWriter.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double ms(Clock::duration d) {
    return std::chrono::duration<double, std::milli>(d).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

} // namespace

class BenchSegmentationDicom : public QObject {
    Q_OBJECT
private slots:
    void tenSegmentsOn140Slices() {
        REQUIRE_DATA(test::kSegmentedCt);
        const Volume ct = loadPath(test::kRealData / test::kSegmentedCt);
        const ReferencedSeries series = readReferencedSeries(test::segmentedCtFiles());
        const Segmentation seg = test::segmentedCt(ct, 5);
        QCOMPARE(seg.segments().size(), std::size_t(10));
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "ten.dcm";
        std::vector<double> write, read;
        std::size_t frames = 0;
        for (int run = 0; run < 5; ++run) {
            const auto t0 = Clock::now();
            frames = writeSegmentationDicom(file, seg, series).frames;
            const auto t1 = Clock::now();
            const ReadSegmentationDicom r = readSegmentationDicom(file, series, ct.geometry());
            const auto t2 = Clock::now();
            QCOMPARE(r.segments.size(), std::size_t(10));
            QVERIFY(*r.segments[3].mask == *seg.segments()[3].mask);
            write.push_back(ms(t1 - t0));
            read.push_back(ms(t2 - t1));
        }
        qInfo("seg_10_segments_140_slices: frames=%zu file_mb=%.1f write_ms=%.0f read_ms=%.0f "
              "(Lucent, median of 5)",
              frames, fs::file_size(file) / 1e6, median(write), median(read));

        const test::DcmjsRun dcmjs = test::writeWithDcmjs(seg, series, dir.path().toStdString());
        if (!dcmjs.ok) {
            qInfo("dcmjs: not run: %s", dcmjs.message.c_str());
            return;
        }
        const auto t0 = Clock::now();
        const ReadSegmentationDicom r = readSegmentationDicom(dcmjs.file, series, ct.geometry());
        const double readDcmjs = ms(Clock::now() - t0);
        QCOMPARE(r.segments.size(), std::size_t(10));
        QVERIFY(*r.segments[3].mask == *seg.segments()[3].mask);
        qInfo("seg_10_segments_140_slices: dcmjs_write_ms=%.0f (node, one run; the CT parsed "
              "first in %.0f ms, not counted) dcmjs_file_mb=%.1f lucent_read_of_dcmjs_ms=%.0f; "
              "Lucent writes in %.3f of dcmjs' time",
              dcmjs.writeMs, dcmjs.parseMs, fs::file_size(dcmjs.file) / 1e6, readDcmjs,
              median(write) / dcmjs.writeMs);
    }
};

QTEST_APPLESS_MAIN(BenchSegmentationDicom)
#include "bench_segmentation_dicom.moc"
