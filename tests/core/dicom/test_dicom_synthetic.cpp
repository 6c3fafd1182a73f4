// DICOM series written by the test with DCMTK, checked voxel by voxel:
// ordering, orientation, duplicates, gaps, bad files, encodings, progress, cancel.
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>
#include <fstream>

#include "core/io/Catalog.h"
#include "tests/support/SyntheticDicom.h"

using namespace lucent;
using test::Encoding;
using test::SyntheticSeries;
namespace fs = std::filesystem;

namespace {

std::vector<glm::dvec3> along(const glm::dvec3& origin, const glm::dvec3& step, int n) {
    std::vector<glm::dvec3> p;
    for (int k = 0; k < n; ++k) {
        p.push_back(origin + step * double(k));
    }
    return p;
}

// Every voxel equals the value the series defines for image `imageOf[k]`.
void verifyVoxels(const Volume& v, const SyntheticSeries& s, const std::vector<int>& imageOf) {
    QCOMPARE(v.dims(), glm::ivec3(s.columns, s.rows, int(imageOf.size())));
    for (int k = 0; k < v.dims().z; ++k) {
        for (int j = 0; j < s.rows; ++j) {
            for (int i = 0; i < s.columns; ++i) {
                if (v.value(i, j, k) != test::expectedValue(s, i, j, imageOf[k])) {
                    QFAIL(qPrintable(QString("voxel (%1,%2,%3): %4, expected %5")
                                         .arg(i)
                                         .arg(j)
                                         .arg(k)
                                         .arg(v.value(i, j, k))
                                         .arg(test::expectedValue(s, i, j, imageOf[k]))));
                }
            }
        }
    }
}

bool near(const glm::dvec3& a, const glm::dvec3& b, double tol = 1e-6) {
    return glm::length(a - b) <= tol;
}

bool anyWarning(const SeriesEntry& e, const char* text) {
    return std::any_of(e.warnings.begin(), e.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

} // namespace

class TestDicomSynthetic : public QObject {
    Q_OBJECT
private slots:
    void shuffledFileNamesAndReversedOrder() {
        QTemporaryDir dir;
        SyntheticSeries s;
        // Written top to bottom with InstanceNumber ascending, names unrelated to position.
        const auto positions = along({-2.0, 3.0, 40.0}, {0, 0, -2.5}, 5);
        std::vector<std::string> names = {"zeta", "alpha", "mid", "b7", "a10"};
        for (int n = 0; n < 5; ++n) {
            test::writeImage(dir.filePath(QString::fromStdString(names[n])).toStdString(), s, n,
                             positions[n], n + 1);
        }
        const Catalog c = scanPath(dir.path().toStdString());
        QCOMPARE(c.series.size(), std::size_t(1));
        const SeriesEntry& e = c.series[0];
        QVERIFY(!e.resampled);
        QVERIFY(e.warnings.empty());
        QVERIFY(near(e.geometry.origin, {-2.0, 3.0, 30.0}));
        QVERIFY(std::abs(e.geometry.spacing.z - 2.5) < 1e-9);
        QVERIFY(near(e.geometry.spacing, {0.5, 0.75, 2.5}));
        const Volume v = loadSeries(e);
        verifyVoxels(v, s, {4, 3, 2, 1, 0}); // ascending along +z: last written first
    }

    void obliqueOrientation() {
        QTemporaryDir dir;
        SyntheticSeries s;
        const double a = glm::radians(30.0);
        s.rowDir = {std::cos(a), std::sin(a), 0.0};
        s.colDir = {0.0, 0.0, -1.0};
        const glm::dvec3 normal = glm::normalize(glm::cross(s.rowDir, s.colDir));
        test::writeSeries(dir.path().toStdString(), s, along({10, 20, 30}, normal * 1.25, 4));
        const Catalog c = scanPath(dir.path().toStdString());
        const SeriesEntry& e = c.series.at(0);
        QVERIFY(!e.resampled);
        QVERIFY(near(e.geometry.direction[0], s.rowDir, 1e-9));
        QVERIFY(near(e.geometry.direction[1], s.colDir, 1e-9));
        QVERIFY(near(e.geometry.direction[2], normal, 1e-9));
        const Volume v = loadSeries(e);
        verifyVoxels(v, s, {0, 1, 2, 3});
        // Voxel (3, 2, 1) sits where the file says: IPP + 3 * 0.5 row + 2 * 0.75 col + 1.25 n.
        const glm::dvec3 expected =
            glm::dvec3(10, 20, 30) + normal * 1.25 + s.rowDir * 1.5 + s.colDir * 1.5;
        QVERIFY(near(v.geometry().toPatient({3, 2, 1}), expected, 1e-6)); // DS holds ~10 digits
    }

    void nonSquareImages() {
        QTemporaryDir dir;
        SyntheticSeries s;
        s.columns = 11;
        s.rows = 5;
        s.pixelSpacing = {0.3, 0.9};
        test::writeSeries(dir.path().toStdString(), s, along({0, 0, 0}, {0, 0, 1}, 3));
        const Volume v = loadPath(dir.path().toStdString());
        QCOMPARE(v.dims(), glm::ivec3(11, 5, 3));
        QVERIFY(near(v.geometry().spacing, {0.3, 0.9, 1.0}));
        verifyVoxels(v, s, {0, 1, 2});
    }

    void duplicateSliceIsDroppedWithWarning() {
        QTemporaryDir dir;
        SyntheticSeries s;
        auto positions = along({0, 0, 0}, {0, 0, 2}, 4);
        positions.push_back(positions[2]); // image 4 repeats image 2's position
        test::writeSeries(dir.path().toStdString(), s, positions);
        const Catalog c = scanPath(dir.path().toStdString());
        const SeriesEntry& e = c.series.at(0);
        QVERIFY(anyWarning(e, "dropped 1 image"));
        QVERIFY(!e.resampled);
        const Volume v = loadSeries(e);
        verifyVoxels(v, s, {0, 1, 2, 3}); // the lower InstanceNumber is kept
    }

    void missingSliceIsInterpolatedWithWarning() {
        QTemporaryDir dir;
        SyntheticSeries s;
        const std::vector<glm::dvec3> positions = {{0, 0, 0}, {0, 0, 1}, {0, 0, 3}, {0, 0, 4}};
        test::writeSeries(dir.path().toStdString(), s, positions);
        const Catalog c = scanPath(dir.path().toStdString());
        const SeriesEntry& e = c.series.at(0);
        QVERIFY(e.resampled);
        QVERIFY(anyWarning(e, "1 missing slice"));
        QCOMPARE(e.geometry.dims, glm::ivec3(8, 6, 5));
        const Volume v = loadSeries(e);
        for (int j = 0; j < s.rows; ++j) {
            for (int i = 0; i < s.columns; ++i) {
                QCOMPARE(v.value(i, j, 0), test::expectedValue(s, i, j, 0));
                QCOMPARE(v.value(i, j, 1), test::expectedValue(s, i, j, 1));
                QCOMPARE(v.value(i, j, 3), test::expectedValue(s, i, j, 2));
                QCOMPARE(v.value(i, j, 4), test::expectedValue(s, i, j, 3));
                const double mid =
                    0.5 * (test::expectedValue(s, i, j, 1) + test::expectedValue(s, i, j, 2));
                QVERIFY(std::abs(v.value(i, j, 2) - mid) <= 0.5);
            }
        }
    }

    void badFilesAreSkippedAndTheSeriesStillLoads() {
        QTemporaryDir dir;
        const std::string d = dir.path().toStdString();
        SyntheticSeries s;
        test::writeSeries(d, s, along({0, 0, 0}, {0, 0, 1}, 4));
        // A truncated copy of a slice at a new position, a file without pixel data, and junk.
        const std::string cut = test::writeImage(d + "/truncated.dcm", s, 9, {0, 0, 4}, 9);
        fs::resize_file(cut, fs::file_size(cut) - 20);
        SyntheticSeries other = s;
        other.seriesUid = "1.2.826.0.1.3680043.2.1125.77";
        test::writeWithoutPixelData(d + "/nopixels.dcm", other);
        std::ofstream(d + "/README.txt") << "not DICOM at all\n";
        fs::create_directories(d + "/sub");
        std::ofstream(d + "/sub/empty.dcm");

        const Catalog c = scanPath(d);
        QCOMPARE(c.series.size(), std::size_t(1));
        QCOMPARE(c.series[0].slices.size(), std::size_t(4));
        auto reason = [&](const std::string& name) -> QString {
            for (const SkippedFile& f : c.skipped) {
                if (fs::path(f.file).filename() == name) {
                    return QString::fromStdString(f.reason);
                }
            }
            return "(not skipped)";
        };
        QVERIFY2(reason("truncated.dcm").contains("truncated pixel data"),
                 qPrintable(reason("truncated.dcm")));
        QVERIFY2(reason("nopixels.dcm").contains("no pixel data"),
                 qPrintable(reason("nopixels.dcm")));
        QVERIFY2(reason("README.txt").contains("not a DICOM file"),
                 qPrintable(reason("README.txt")));
        QVERIFY2(reason("empty.dcm").contains("not a DICOM file"), qPrintable(reason("empty.dcm")));
        verifyVoxels(loadSeries(c.series[0]), s, {0, 1, 2, 3});
    }

    void nothingLoadableSaysWhy() {
        QTemporaryDir dir;
        std::ofstream(dir.filePath("junk.bin").toStdString()) << "\x01\x02garbage";
        try {
            loadPath(dir.path().toStdString());
            QFAIL("expected LoadError");
        } catch (const LoadError& e) {
            QVERIFY2(QString(e.what()).contains("junk.bin"), e.what());
            QVERIFY(QString(e.what()).contains("nothing loadable"));
        }
        QVERIFY_THROWS_EXCEPTION(LoadError, scanPath("/nonexistent/lucent/path"));
    }

    void singleSliceSeriesIsAnImage() {
        QTemporaryDir dir;
        SyntheticSeries s;
        test::writeSeries(dir.path().toStdString(), s, {{5, 6, 7}});
        const Catalog c = scanPath(dir.path().toStdString());
        QCOMPARE(c.series.at(0).kind, SeriesKind::Image);
        QCOMPARE(c.series[0].geometry.dims, glm::ivec3(8, 6, 1));
        verifyVoxels(loadSeries(c.series[0]), s, {0});
    }

    void imagesWithoutGeometryAreSeparateImages() {
        QTemporaryDir dir;
        SyntheticSeries s;
        s.withGeometry = false;
        test::writeSeries(dir.path().toStdString(), s, along({0, 0, 0}, {0, 0, 1}, 3));
        const Catalog c = scanPath(dir.path().toStdString());
        QCOMPARE(c.series.size(), std::size_t(3));
        for (std::size_t n = 0; n < 3; ++n) {
            const SeriesEntry& e = c.series[n];
            QCOMPARE(e.kind, SeriesKind::Image);
            QCOMPARE(e.geometry.dims, glm::ivec3(8, 6, 1));
            QVERIFY(anyWarning(e, "no ImagePositionPatient"));
            QVERIFY(!anyWarning(e, "dropped"));
            QCOMPARE(loadSeries(e).dims(), glm::ivec3(8, 6, 1));
        }
        QVERIFY(c.skipped.empty());
    }

    void localizerInSameSeriesIsSeparate() {
        QTemporaryDir dir;
        SyntheticSeries s;
        test::writeSeries(dir.path().toStdString(), s, along({0, 0, 0}, {0, 0, 1}, 3));
        SyntheticSeries scout = s;
        scout.imageType = "ORIGINAL\\PRIMARY\\LOCALIZER";
        scout.rowDir = {0, 1, 0};
        scout.colDir = {0, 0, -1};
        test::writeImage(dir.filePath("scout.dcm").toStdString(), scout, 0, {0, -10, 50}, 100);
        const Catalog c = scanPath(dir.path().toStdString());
        QCOMPARE(c.series.size(), std::size_t(2));
        QCOMPARE(c.series[0].kind, SeriesKind::Volume);
        QCOMPARE(c.series[0].slices.size(), std::size_t(3));
        QCOMPARE(c.series[1].kind, SeriesKind::Localizer);
        QCOMPARE(c.series[1].id, s.seriesUid + "#2");
    }

    void encodings_data() {
        QTest::addColumn<int>("encoding");
        QTest::addColumn<bool>("isSigned");
        QTest::newRow("implicit-le") << int(Encoding::ImplicitLittle) << false;
        QTest::newRow("explicit-be") << int(Encoding::ExplicitBig) << false;
        QTest::newRow("explicit-be-signed") << int(Encoding::ExplicitBig) << true;
        QTest::newRow("deflated") << int(Encoding::Deflated) << false;
        QTest::newRow("jpeg-lossless") << int(Encoding::JpegLossless) << false;
        QTest::newRow("rle-signed") << int(Encoding::Rle) << true;
    }
    void encodings() {
        QFETCH(int, encoding);
        QFETCH(bool, isSigned);
        QTemporaryDir dir;
        SyntheticSeries s;
        s.encoding = Encoding(encoding);
        s.isSigned = isSigned;
        s.bitsStored = 16;
        if (isSigned) {
            s.intercept = 0;
            s.stored = [](int i, int j, int k) { return (i * 97 - j * 131 + k * 7) * 11 - 2000; };
        }
        test::writeSeries(dir.path().toStdString(), s, along({0, 0, 0}, {0, 0, 1}, 3));
        verifyVoxels(loadPath(dir.path().toStdString()), s, {0, 1, 2});
    }

    void jpegBaselineWithinBound() {
        QTemporaryDir dir;
        SyntheticSeries s;
        s.encoding = Encoding::JpegBaseline;
        s.bitsAllocated = 8;
        s.bitsStored = 8;
        s.intercept = 0;
        s.columns = s.rows = 16;
        s.stored = [](int i, int j, int k) {
            return 40 + i * 6 + j * 3 + k;
        }; // smooth: JPEG-friendly
        test::writeSeries(dir.path().toStdString(), s, along({0, 0, 0}, {0, 0, 1}, 2));
        const Volume v = loadPath(dir.path().toStdString());
        double worst = 0.0;
        for (int k = 0; k < 2; ++k) {
            for (int j = 0; j < 16; ++j) {
                for (int i = 0; i < 16; ++i) {
                    worst = std::max(worst,
                                     std::abs(v.value(i, j, k) - test::expectedValue(s, i, j, k)));
                }
            }
        }
        QVERIFY2(worst <= 8.0, qPrintable(QString::number(worst)));
    }

    void bitsAboveBitsStoredAreIgnored() {
        QTemporaryDir dir;
        SyntheticSeries s;
        s.bitsStored = 12;
        s.dirtyHighBits = true;
        test::writeSeries(dir.path().toStdString(), s, along({0, 0, 0}, {0, 0, 1}, 2));
        const Volume v = loadPath(dir.path().toStdString());
        QCOMPARE(v.type(), VoxelType::Int16);
        verifyVoxels(v, s, {0, 1});
    }

    void fractionalRescaleGivesFloat() {
        QTemporaryDir dir;
        SyntheticSeries s;
        s.modality = "MR";
        s.slope = 0.25;
        s.intercept = 1.5;
        test::writeSeries(dir.path().toStdString(), s, along({0, 0, 0}, {0, 0, 1}, 2));
        const Volume v = loadPath(dir.path().toStdString());
        QCOMPARE(v.type(), VoxelType::Float32);
        verifyVoxels(v, s, {0, 1});
    }

    void sixteenBitCtNarrowsToInt16() {
        QTemporaryDir dir;
        SyntheticSeries s;
        s.bitsStored = 16; // declared range 0..65535 minus 1024 does not fit int16; the data do
        test::writeSeries(dir.path().toStdString(), s, along({0, 0, 0}, {0, 0, 1}, 2));
        const Volume v = loadPath(dir.path().toStdString());
        QCOMPARE(v.type(), VoxelType::Int16);
        verifyVoxels(v, s, {0, 1});
    }

    void dicomdirListsTheFilesToLoad() {
        QTemporaryDir dir;
        const std::string root = dir.path().toStdString();
        fs::create_directories(root + "/DCM/S1");
        SyntheticSeries s;
        const auto positions = along({0, 0, 0}, {0, 0, 1.5}, 3);
        std::vector<std::string> listed;
        for (int n = 2; n >= 0; --n) {
            const std::string rel = "DCM/S1/IM" + std::to_string(n);
            test::writeImage(root + "/" + rel, s, n, positions[n], n + 1);
            listed.push_back(rel);
        }
        // A stray image of another series in the same tree, not in the DICOMDIR.
        SyntheticSeries stray = s;
        stray.seriesUid = "1.2.826.0.1.3680043.2.1125.55";
        test::writeImage(root + "/DCM/STRAY", stray, 0, {0, 0, 0}, 1);
        const std::string dicomdir = test::writeDicomdir(root, listed);
        const Catalog c = scanPath(dicomdir);
        QCOMPARE(c.series.size(), std::size_t(1));
        QCOMPARE(c.series[0].seriesUid, s.seriesUid);
        QVERIFY(std::abs(c.series[0].geometry.spacing.z - 1.5) < 1e-9);
        verifyVoxels(loadSeries(c.series[0]), s, {0, 1, 2});
    }

    void mixedImageSizesInOneSeriesAreSeparateEntries() {
        QTemporaryDir dir;
        SyntheticSeries s;
        test::writeSeries(dir.path().toStdString(), s, along({0, 0, 0}, {0, 0, 1}, 3), "a");
        SyntheticSeries wide = s;
        wide.columns = 12;
        test::writeSeries(dir.path().toStdString(), wide, along({0, 0, 10}, {0, 0, 1}, 2), "b");
        const Catalog c = scanPath(dir.path().toStdString());
        QCOMPARE(c.series.size(), std::size_t(2));
        QCOMPARE(c.series[0].geometry.dims, glm::ivec3(8, 6, 3));
        QCOMPARE(c.series[1].geometry.dims, glm::ivec3(12, 6, 2));
        verifyVoxels(loadSeries(c.series[0]), s, {0, 1, 2});
        verifyVoxels(loadSeries(c.series[1]), wide, {0, 1});
    }

    void truncatedHeadersAreReportedNotFatal() {
        // GDCM as packaged aborts on headers cut short; every cut must be a clean skip.
        QTemporaryDir dir;
        SyntheticSeries s;
        const std::string whole =
            test::writeImage(dir.filePath("whole.dcm").toStdString(), s, 0, {0, 0, 0}, 1);
        const auto size = fs::file_size(whole);
        QTemporaryDir cuts;
        for (std::uintmax_t n = 1; n < size; n += 7) {
            const std::string cut = cuts.filePath(QString("cut%1.dcm").arg(n)).toStdString();
            fs::copy_file(whole, cut);
            fs::resize_file(cut, n);
        }
        const Catalog c = scanPath(cuts.path().toStdString());
        QVERIFY(c.series.empty());
        QCOMPARE(c.skipped.size(), std::size_t((size - 2) / 7 + 1));
        for (const SkippedFile& f : c.skipped) {
            QVERIFY2(!f.reason.empty(), f.file.c_str());
        }
    }

    void undecodablePixelDataNamesTheFile() {
        // A JPEG lossless image whose start-of-frame marker is destroyed.
        QTemporaryDir dir;
        SyntheticSeries s;
        s.encoding = Encoding::JpegLossless;
        const std::string file =
            test::writeImage(dir.filePath("broken.dcm").toStdString(), s, 0, {0, 0, 0}, 1);
        std::string bytes;
        {
            std::ifstream in(file, std::ios::binary);
            bytes.assign(std::istreambuf_iterator<char>(in), {});
        }
        const std::size_t sof = bytes.find("\xFF\xC3");
        QVERIFY(sof != std::string::npos);
        bytes[sof + 1] = '\x01';
        std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
        try {
            loadPath(dir.path().toStdString());
            QFAIL("expected LoadError");
        } catch (const LoadError& e) {
            QVERIFY2(QString(e.what()).contains("broken.dcm"), e.what());
        }
    }

    void unsupportedTransferSyntaxIsNamed() {
        // JPEG lossless relabelled as JPIP Referenced (same UID length): not decodable here.
        QTemporaryDir dir;
        SyntheticSeries s;
        s.encoding = Encoding::JpegLossless;
        const std::string file =
            test::writeImage(dir.filePath("jpip.dcm").toStdString(), s, 0, {0, 0, 0}, 1);
        std::string bytes;
        {
            std::ifstream in(file, std::ios::binary);
            bytes.assign(std::istreambuf_iterator<char>(in), {});
        }
        const std::size_t at = bytes.find("1.2.840.10008.1.2.4.70");
        QVERIFY(at != std::string::npos);
        bytes.replace(at, 22, "1.2.840.10008.1.2.4.94");
        std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
        const Catalog c = scanPath(dir.path().toStdString());
        QVERIFY(c.series.empty());
        QCOMPARE(c.skipped.size(), std::size_t(1));
        QCOMPARE(c.skipped[0].reason,
                 std::string("unsupported transfer syntax 1.2.840.10008.1.2.4.94"));
    }

    void zeroSizeImageIsSkipped() {
        QTemporaryDir dir;
        SyntheticSeries s;
        s.columns = 0;
        test::writeImage(dir.filePath("empty.dcm").toStdString(), s, 0, {0, 0, 0}, 1);
        const Catalog c = scanPath(dir.path().toStdString());
        QVERIFY(c.series.empty());
        QCOMPARE(c.skipped.size(), std::size_t(1));
        QVERIFY2(QString::fromStdString(c.skipped[0].reason).contains("zero-size image"),
                 c.skipped[0].reason.c_str());
    }

    void progressIsReportedAndCancelStops() {
        QTemporaryDir dir;
        SyntheticSeries s;
        test::writeSeries(dir.path().toStdString(), s, along({0, 0, 0}, {0, 0, 1}, 12));
        std::vector<LoadProgress> seen;
        std::mutex m;
        LoadControl control;
        control.onProgress = [&](const LoadProgress& p) {
            const std::lock_guard lock(m);
            seen.push_back(p);
        };
        const Catalog c = scanPath(dir.path().toStdString(), control);
        loadSeries(c.series.at(0), control);
        for (const auto& p : seen) {
            QCOMPARE(p.total, std::size_t(12));
        }
        auto last = [&](const char* stage) {
            std::size_t done = 0;
            for (const auto& p : seen) {
                if (p.stage == stage) {
                    done = std::max(done, p.done);
                }
            }
            return done;
        };
        QCOMPARE(last("scanning"), std::size_t(12));
        QCOMPARE(last("decoding"), std::size_t(12));

        std::stop_source source;
        LoadControl cancelling;
        cancelling.stop = source.get_token();
        cancelling.onProgress = [&](const LoadProgress&) { source.request_stop(); };
        QVERIFY_THROWS_EXCEPTION(LoadCancelled, loadSeries(c.series[0], cancelling));
        source.request_stop();
        QVERIFY_THROWS_EXCEPTION(LoadCancelled, scanPath(dir.path().toStdString(), cancelling));
    }
};

QTEST_APPLESS_MAIN(TestDicomSynthetic)
#include "test_dicom_synthetic.moc"
