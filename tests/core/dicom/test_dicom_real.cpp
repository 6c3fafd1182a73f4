// DICOM loading on the real data in ../shared/data: geometry, HU, localizers,
// tilt and uneven gaps checked against the files, every transfer syntax of
// NEMA WG04, Enhanced MR multi-frame.
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>
#include <random>

#include "core/io/Catalog.h"
#include "tests/support/RealData.h"
#include "tests/support/ReferenceDicom.h"
#include "tests/support/RtDoseFromImage.h"
#include "tests/support/SyntheticDicom.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

const fs::path kData = test::kRealData;

std::vector<const SeriesEntry*> entriesOfKind(const Catalog& c, SeriesKind kind) {
    std::vector<const SeriesEntry*> out;
    for (const SeriesEntry& e : c.series) {
        if (e.kind == kind) {
            out.push_back(&e);
        }
    }
    return out;
}

bool hasWarning(const SeriesEntry& e, const QString& text) {
    return std::any_of(e.warnings.begin(), e.warnings.end(), [&](const std::string& w) {
        return QString::fromStdString(w).contains(text);
    });
}

// For voxels of a resampled volume, the value the files give at the voxel's
// patient position: bilinear in the file's own plane, linear between the two
// files whose planes bracket it. Checks geometry and resampling together.
struct ResampleCheck {
    int compared = 0;
    double maxError = 0.0;
};

ResampleCheck compareWithFiles(const Volume& v, const std::vector<test::ReferenceImage>& files,
                               int samples) {
    const glm::dvec3 n = v.geometry().direction[2];
    std::vector<const test::ReferenceImage*> sorted;
    for (const auto& f : files) {
        sorted.push_back(&f);
    }
    std::sort(sorted.begin(), sorted.end(), [&](auto* a, auto* b) {
        return glm::dot(a->position, n) < glm::dot(b->position, n);
    });
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> di(0, v.dims().x - 1), dj(0, v.dims().y - 1),
        dk(0, v.dims().z - 1);
    ResampleCheck check;
    for (int s = 0; s < samples * 20 && check.compared < samples; ++s) {
        const glm::ivec3 ijk(di(rng), dj(rng), dk(rng));
        const glm::dvec3 p = v.geometry().toPatient(glm::dvec3(ijk));
        const double d = glm::dot(p, n);
        std::size_t hi = 0;
        while (hi < sorted.size() && glm::dot(sorted[hi]->position, n) < d - 1e-4) {
            ++hi;
        }
        double expected = 0.0, dist = 0.0;
        if (hi < sorted.size() && std::abs(glm::dot(sorted[hi]->position, n) - d) <= 1e-4) {
            if (!sorted[hi]->sample(p, expected, dist)) {
                continue;
            }
        } else {
            if (hi == 0 || hi == sorted.size()) {
                continue;
            }
            const auto* a = sorted[hi - 1];
            const auto* b = sorted[hi];
            const double da = glm::dot(a->position, n), db = glm::dot(b->position, n);
            const double w = (d - da) / (db - da);
            double va = 0.0, vb = 0.0;
            // The point projected along the normal onto each bracketing plane.
            if (!a->sample(p - n * (d - da), va, dist) || !b->sample(p - n * (d - db), vb, dist)) {
                continue;
            }
            expected = (1 - w) * va + w * vb;
        }
        check.maxError =
            std::max(check.maxError, std::abs(v.value(ijk.x, ijk.y, ijk.z) - expected));
        ++check.compared;
    }
    return check;
}

std::vector<test::ReferenceImage> readFolder(const fs::path& dir) {
    std::vector<test::ReferenceImage> out;
    for (const auto& f : fs::directory_iterator(dir)) {
        out.push_back(test::readReferenceImage(f.path().string()));
    }
    return out;
}

Volume loadOnly(const fs::path& p) {
    return loadPath(p);
}

// The oblique MR of the defect report, with real MR pixels (NEMA MR1, every
// other pixel, a different phase per image): 20 images of 256x256 at 0.86 mm,
// 7 mm apart give or take 0.05 mm, the plane 8 degrees from axial, drifting
// `drift` mm in plane over the stack. Returns the stored value of (i, j, image).
std::function<int(int, int, int)> writeObliqueMr(const fs::path& dir, const Volume& mr,
                                                 double drift) {
    test::SyntheticSeries s;
    s.modality = "MR";
    s.imageType = "ORIGINAL\\PRIMARY\\M";
    s.columns = s.rows = 256;
    s.pixelSpacing = {0.86, 0.86};
    s.bitsStored = 16;
    s.intercept = 0.0;
    const double a = glm::radians(8.0);
    s.colDir = {0.0, std::cos(a), std::sin(a)};
    s.stored = [&mr](int i, int j, int image) {
        return int(mr.value(2 * i + image % 2, 2 * j + (image / 2) % 2, 0));
    };
    const glm::dvec3 normal = glm::cross(s.rowDir, s.colDir);
    std::vector<glm::dvec3> positions;
    double z = 0.0;
    for (int k = 0; k < 20; ++k) {
        positions.push_back(glm::dvec3(-110.0, -95.0, -40.0) + normal * z +
                            s.colDir * (drift * k / 19.0));
        z += 7.0 + 0.05 * std::sin(1.7 * k);
    }
    test::writeSeries(dir.string(), s, positions);
    return s.stored;
}

} // namespace

class TestDicomReal : public QObject {
    Q_OBJECT
private slots:
    void philips140SliceCt() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2020");
        const Catalog c = scanPath(kData / "dcm_qa_ct/Philips_S21570/S2020");
        QCOMPARE(c.series.size(), std::size_t(1));
        const SeriesEntry& e = c.series[0];
        QCOMPARE(e.kind, SeriesKind::Volume);
        QCOMPARE(e.modality, std::string("CT"));
        QCOMPARE(e.geometry.dims, glm::ivec3(512, 512, 140));
        QCOMPARE(e.geometry.spacing.x, 0.451171875);
        QCOMPARE(e.geometry.spacing.y, 0.451171875);
        QVERIFY(std::abs(e.geometry.spacing.z - 1.0) < 1e-6);
        QVERIFY(!e.resampled);
        QVERIFY(e.warnings.empty());
        QVERIFY(glm::length(e.geometry.direction[2] - glm::dvec3(0, 0, 1)) < 1e-9);

        const Volume v = loadSeries(e);
        QCOMPARE(v.type(), VoxelType::Int16);
        const auto [lo, hi] = v.valueRange();
        // 12-bit unsigned with intercept -1024: HU in [-1024, 3071], air and bone both present.
        QVERIFY2(lo >= -1024 && lo <= -900, qPrintable(QString::number(lo)));
        QVERIFY2(hi > 1000 && hi <= 3071, qPrintable(QString::number(hi)));

        // The lowest slice's first pixels equal the file's, at the file's position.
        const test::ReferenceImage first = test::readReferenceImage(e.slices.front().file);
        QVERIFY(glm::length(v.geometry().origin - first.position) < 1e-9);
        for (int j = 200; j < 300; j += 17) {
            for (int i = 100; i < 400; i += 23) {
                QCOMPARE(v.value(i, j, 0), first.at(i, j));
            }
        }
        const test::ReferenceImage last = test::readReferenceImage(e.slices.back().file);
        const glm::dvec3 lastIndex = v.geometry().toIndex(last.position);
        QVERIFY(glm::length(lastIndex - glm::dvec3(0, 0, 139)) < 1e-6);
        QCOMPARE(v.value(256, 256, 139), last.at(256, 256));
    }

    void localizerIsItsOwnEntry() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570");
        const Catalog c = scanPath(kData / "dcm_qa_ct/Philips_S21570");
        const auto localizers = entriesOfKind(c, SeriesKind::Localizer);
        const auto volumes = entriesOfKind(c, SeriesKind::Volume);
        QCOMPARE(localizers.size(), std::size_t(1));
        QCOMPARE(volumes.size(), std::size_t(2));
        QCOMPARE(localizers[0]->geometry.dims, glm::ivec3(512, 256, 1));
        QCOMPARE(c.defaultEntry()->geometry.dims, glm::ivec3(512, 512, 140));
        QCOMPARE(c.find(localizers[0]->seriesUid), localizers[0]);
    }

    void philipsTiltIsResampledRight() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21610/S2010");
        const fs::path dir = kData / "dcm_qa_ct/Philips_S21610/S2010";
        const Catalog c = scanPath(dir);
        QCOMPARE(c.series.size(), std::size_t(1));
        const SeriesEntry& e = c.series[0];
        QVERIFY(e.resampled);
        QVERIFY2(hasWarning(e, "gantry tilt 18.5"),
                 e.warnings.empty() ? "none" : e.warnings[0].c_str());
        QCOMPARE(e.geometry.dims.z, 54);
        // The grid runs along the slice normal, orthonormal.
        const glm::dmat3 d = e.geometry.direction;
        QVERIFY(std::abs(glm::dot(d[0], d[1])) < 1e-9 && std::abs(glm::dot(d[1], d[2])) < 1e-9);
        const Volume v = loadSeries(e);
        const ResampleCheck check = compareWithFiles(v, readFolder(dir), 400);
        QVERIFY(check.compared >= 400);
        // Rounded to integer HU after bilinear interpolation: within half a unit.
        QVERIFY2(check.maxError <= 0.5 + 1e-9, qPrintable(QString::number(check.maxError)));
    }

    void geTiltAndUnevenGapsAreResampledRight() {
        REQUIRE_DATA("dcm_qa_ct/GE_head_tilt_varspacing");
        const fs::path dir = kData / "dcm_qa_ct/GE_head_tilt_varspacing";
        const Catalog c = scanPath(dir);
        QCOMPARE(c.series.size(), std::size_t(1));
        const SeriesEntry& e = c.series[0];
        QVERIFY(e.resampled);
        QVERIFY(hasWarning(e, "gantry tilt 18.5"));
        QVERIFY(hasWarning(e, "uneven slice gaps"));
        const Volume v = loadSeries(e);
        QCOMPARE(v.type(), VoxelType::Int16);
        const ResampleCheck check = compareWithFiles(v, readFolder(dir), 400);
        QVERIFY(check.compared >= 400);
        QVERIFY2(check.maxError <= 0.5 + 1e-6, qPrintable(QString::number(check.maxError)));
    }

    void nemaLosslessMatchesUncompressed_data() {
        QTest::addColumn<QString>("set");
        QTest::addColumn<QString>("variant");
        for (const char* set : {"CT1", "CT2", "MR1"}) {
            for (const char* variant : {"JPLL", "JLSL", "J2KR", "RLE"}) {
                QTest::newRow(qPrintable(QString("%1_%2").arg(set, variant))) << set << variant;
            }
        }
    }
    void nemaLosslessMatchesUncompressed() {
        QFETCH(QString, set);
        QFETCH(QString, variant);
        REQUIRE_DATA("nema_wg04");
        const fs::path dir = kData / "nema_wg04" / set.toStdString();
        const Volume unc = loadOnly(dir / (set + "_UNC.dcm").toStdString());
        const Volume v = loadOnly(dir / (set + "_" + variant + ".dcm").toStdString());
        QCOMPARE(v.dims(), unc.dims());
        QCOMPARE(v.type(), unc.type());
        QVERIFY(std::equal(v.bytes().begin(), v.bytes().end(), unc.bytes().begin()));
        QVERIFY(unc.valueRange().second > unc.valueRange().first);
    }

    // An RLE RT dose made from the real NEMA MR: GDCM's image helpers assert on
    // its grid frame offsets, and on a frame count of another VR, and those
    // assertions aborted the whole process. Each one now loads, pixel for pixel.
    void obliqueMrWithinTolerancesKeepsItsAcquiredGrid() {
        REQUIRE_DATA("nema_wg04/MR1/MR1_UNC.dcm");
        const Volume mr = loadOnly(kData / "nema_wg04/MR1/MR1_UNC.dcm");
        QTemporaryDir dir;
        // 0.056 mm over 133 mm: 0.024 degrees off the normal, 0.065 pixel.
        const auto stored = writeObliqueMr(dir.path().toStdString(), mr, 0.056);
        const Catalog c = scanPath(dir.path().toStdString());
        QCOMPARE(c.series.size(), std::size_t(1));
        const SeriesEntry& e = c.series[0];
        QVERIFY(!e.resampled);
        QCOMPARE(e.geometry.dims, glm::ivec3(256, 256, 20));
        QVERIFY(hasWarning(e, "0.024 deg off the normal"));
        QVERIFY(hasWarning(e, "slice gaps vary"));
        QVERIFY(std::abs(e.geometry.spacing.z - 7.0) < 0.01);
        // The acquired pixels, untouched by any interpolation.
        const Volume v = loadSeries(e);
        for (int k = 0; k < 20; ++k) {
            for (int j = 0; j < 256; j += 5) {
                for (int i = 0; i < 256; i += 3) {
                    if (v.value(i, j, k) != stored(i, j, k)) {
                        QFAIL(qPrintable(QString("voxel (%1,%2,%3): %4, the file has %5")
                                             .arg(i)
                                             .arg(j)
                                             .arg(k)
                                             .arg(v.value(i, j, k))
                                             .arg(stored(i, j, k))));
                    }
                }
            }
        }
    }

    void obliqueMrBeyondTheShiftToleranceIsResampledRight() {
        REQUIRE_DATA("nema_wg04/MR1/MR1_UNC.dcm");
        const Volume mr = loadOnly(kData / "nema_wg04/MR1/MR1_UNC.dcm");
        QTemporaryDir dir;
        // A third of a pixel over the stack: beyond the quarter-pixel tolerance.
        writeObliqueMr(dir.path().toStdString(), mr, 0.86 / 3.0);
        const Catalog c = scanPath(dir.path().toStdString());
        const SeriesEntry& e = c.series.at(0);
        QVERIFY(e.resampled);
        QCOMPARE(e.geometry.dims, glm::ivec3(256, 257, 20));
        QVERIFY(hasWarning(e, "gantry tilt"));
        const Volume v = loadSeries(e);
        const ResampleCheck check = compareWithFiles(v, readFolder(dir.path().toStdString()), 400);
        QVERIFY(check.compared >= 400);
        QVERIFY2(check.maxError <= 0.5 + 1e-6, qPrintable(QString::number(check.maxError)));
    }

    void rtDoseThatGdcmHelpersAssertOnLoads_data() {
        QTest::addColumn<int>("flaw");
        QTest::newRow("valid") << int(test::RtDoseFlaw::None);
        QTest::newRow("frame count as US") << int(test::RtDoseFlaw::FrameCountAsUS);
        QTest::newRow("frame count as FD") << int(test::RtDoseFlaw::FrameCountAsFD);
        QTest::newRow("no grid offsets") << int(test::RtDoseFlaw::NoGridOffsets);
    }
    void rtDoseThatGdcmHelpersAssertOnLoads() {
        QFETCH(int, flaw);
        REQUIRE_DATA("nema_wg04");
        const fs::path source = kData / "nema_wg04/MR1/MR1_UNC.dcm";
        QTemporaryDir dir;
        const std::string file = test::writeRtDoseFromImage(
            source.string(), dir.filePath("dose.dcm").toStdString(), test::RtDoseFlaw(flaw));
        const Volume unc = loadOnly(source);
        try {
            const Volume dose = loadOnly(file);
            QCOMPARE(dose.dims(), unc.dims());
            QVERIFY(std::equal(dose.bytes().begin(), dose.bytes().end(), unc.bytes().begin()));
        } catch (const std::exception& e) {
            QFAIL(e.what());
        }
    }

    void nemaLossyWithinBound_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<double>("maxAbs");
        QTest::addColumn<double>("minPsnr");
        // Near-lossless JPEG-LS bounds each error by its NEAR parameter (4 here);
        // JPEG 2000 lossy and 12-bit lossy JPEG are bounded by PSNR over the
        // uncompressed image's value range (measured: J2KI 38-41 dB, JPLY 48 dB).
        for (const char* set : {"CT1", "CT2", "MR1"}) {
            QTest::newRow(qPrintable(QString("%1_JLSN").arg(set)))
                << QString("%1/%1_JLSN").arg(set) << 4.0 << 55.0;
            QTest::newRow(qPrintable(QString("%1_J2KI").arg(set)))
                << QString("%1/%1_J2KI").arg(set) << 1e9 << 33.0;
        }
        QTest::newRow("MR1_JPLY") << QString("MR1/MR1_JPLY") << 1e9 << 40.0;
    }
    void nemaLossyWithinBound() {
        QFETCH(QString, file);
        QFETCH(double, maxAbs);
        QFETCH(double, minPsnr);
        REQUIRE_DATA("nema_wg04");
        const fs::path dir = kData / "nema_wg04";
        const QString set = file.section('/', 0, 0);
        const Volume unc = loadOnly(dir / (set + "/" + set + "_UNC.dcm").toStdString());
        const Volume v = loadOnly(dir / (file + ".dcm").toStdString());
        QCOMPARE(v.dims(), unc.dims());
        double worst = 0.0, sq = 0.0;
        const glm::ivec3 d = v.dims();
        for (int j = 0; j < d.y; ++j) {
            for (int i = 0; i < d.x; ++i) {
                const double e = v.value(i, j, 0) - unc.value(i, j, 0);
                worst = std::max(worst, std::abs(e));
                sq += e * e;
            }
        }
        const double rms = std::sqrt(sq / (double(d.x) * d.y));
        const auto [lo, hi] = unc.valueRange();
        const double psnr = 20.0 * std::log10((hi - lo) / rms);
        qInfo("%s: max |error| %.1f, RMS %.2f, PSNR %.1f dB over range %.0f", qPrintable(file),
              worst, rms, psnr, hi - lo);
        QVERIFY(worst > 0.0); // lossy really is lossy: the comparison is not vacuous
        QVERIFY2(worst <= maxAbs, qPrintable(QString::number(worst)));
        QVERIFY2(psnr >= minPsnr, qPrintable(QString::number(psnr)));
    }

    void enhancedMrPhilipsSplitsFrameTypes() {
        REQUIRE_DATA("dcm_qa_enh/Philips_IM_0027_fMAP.dcm");
        const Catalog c = scanPath(kData / "dcm_qa_enh/Philips_IM_0027_fMAP.dcm");
        const auto volumes = entriesOfKind(c, SeriesKind::Volume);
        QCOMPARE(volumes.size(), std::size_t(2)); // magnitude and field map, 32 frames each
        for (const SeriesEntry* e : volumes) {
            QCOMPARE(e->geometry.dims, glm::ivec3(64, 64, 32));
            QVERIFY(std::abs(e->geometry.spacing.x - 4.0) < 1e-9);
            QVERIFY(std::abs(e->geometry.spacing.z - 4.0) < 1e-3);
            QVERIFY(!e->resampled);
            // The lowest frame's position, from the per-frame functional groups.
            QVERIFY(std::abs(e->geometry.origin.z - (-38.3545908)) < 1e-3);
            QVERIFY(std::abs(e->geometry.origin.x - (-127.24297738)) < 1e-6);
            const Volume v = loadSeries(*e);
            QCOMPARE(v.type(), VoxelType::Float32); // slope 1.2798...
            QVERIFY(v.valueRange().second > v.valueRange().first);
        }
        QVERIFY(volumes[0]->description != volumes[1]->description);
    }

    void enhancedMrSiemensOneVolumePerFile() {
        REQUIRE_DATA("dcm_qa_enh/Siemens_XA10");
        const Catalog c = scanPath(kData / "dcm_qa_enh/Siemens_XA10");
        const auto volumes = entriesOfKind(c, SeriesKind::Volume);
        QCOMPARE(volumes.size(), std::size_t(4));
        for (const SeriesEntry* e : volumes) {
            QCOMPARE(e->geometry.dims, glm::ivec3(64, 64, 6));
            QVERIFY(std::abs(e->geometry.spacing.x - 3.375) < 1e-9);
            QVERIFY(std::abs(e->geometry.spacing.z - 2.4) < 1e-3);
            QVERIFY(std::abs(e->geometry.origin.z - (-5.40356)) < 1e-4);
            QCOMPARE(e->slices.size(), std::size_t(6));
            QCOMPARE(e->slices.front().frame, 0);
        }
        const Volume v = loadSeries(*volumes[0]);
        QCOMPARE(v.type(), VoxelType::Int16); // 12-bit unsigned fits int16 exactly
        QVERIFY(v.valueRange().first >= 0 && v.valueRange().second > 0);
    }

    void ctThreeSlicesAndSegmentationSkipped() {
        REQUIRE_DATA("dcmqi_ct3slice");
        const Catalog c = scanPath(kData / "dcmqi_ct3slice");
        const auto volumes = entriesOfKind(c, SeriesKind::Volume);
        QCOMPARE(volumes.size(), std::size_t(1));
        QCOMPARE(volumes[0]->geometry.dims, glm::ivec3(512, 512, 3));
        const auto seg = std::find_if(c.skipped.begin(), c.skipped.end(), [](const SkippedFile& s) {
            return s.file.find("liver_seg.dcm") != std::string::npos;
        });
        QVERIFY(seg != c.skipped.end());
        QVERIFY(QString::fromStdString(seg->reason).contains("Segmentation"));
        const Volume v = loadSeries(*volumes[0]);
        QVERIFY(v.valueRange().first <= -1000); // signed storage, intercept -1024
    }
};

QTEST_APPLESS_MAIN(TestDicomReal)
#include "test_dicom_real.moc"
