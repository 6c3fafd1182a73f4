// DICOM SEG on the real 140-slice CT: five segments (one empty, one coded outside Lucent's
// table, a UTF-8 name) written, checked by dciodvfy and by reading the file's own attributes,
// read back equal voxel for voxel with names, codes, colours and algorithms; dcmqi's liver SEG
// opened on its three CT slices on the voxels its frames hold (decoded here with dcmdata);
// broken SEGs named in the error.
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <fstream>
#include <random>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include "core/segdicom/SegmentationDicom.h"
#include "tests/core/segdicom/SegFileChecks.h"
#include "tests/core/segdicom/SegmentedCt.h"
#include "tests/segdicom/DcmjsWriter.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

constexpr const char* kDcmqi = "dcmqi_ct3slice";

// The error readSegmentationDicom throws ("" when it reads).
std::string readError(const fs::path& file, const ReferencedSeries& series,
                      const VolumeGeometry& grid) {
    try {
        readSegmentationDicom(file, series, grid);
    } catch (const SegmentationDicomError& e) {
        return e.what();
    }
    return {};
}

} // namespace

class TestSegmentationDicom : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    Volume ct_;
    ReferencedSeries series_;
    fs::path written_;

private slots:
    void initTestCase() {
        REQUIRE_DATA(test::kSegmentedCt);
        ct_ = loadPath(test::kRealData / test::kSegmentedCt);
        series_ = readReferencedSeries(test::segmentedCtFiles());
        QCOMPARE(series_.images.size(), std::size_t(140));
        written_ = fs::path(dir_.path().toStdString()) / "ct.seg.dcm";
    }

    void writesAValidSeg() {
        const Segmentation seg = test::segmentedCt(ct_);
        const WrittenSegmentation w = writeSegmentationDicom(written_, seg, series_);
        QCOMPARE(w.frames, test::nonEmptySlices(seg));
        QVERIFY(!fs::exists(written_.string() + ".part"));
        const QStringList complaints = test::dciodvfyComplaints(written_);
        QVERIFY2(complaints.isEmpty(), qPrintable(complaints.join('\n')));
        // What the file says, read here with dcmdata, not with Lucent's reader.
        test::checkSegFile(written_, seg, series_, ct_.geometry());
        QVERIFY(!QTest::currentTestFailed());
    }

    // No voxel at all: an empty frame per segment keeps them described and the SEG valid
    // (dcmseg 3.6.7 wants no fewer frames than segments).
    void writesSegmentsWithNoVoxel() {
        Segmentation seg(ct_.geometry());
        seg.add("Liver, to do", findSegmentKind("liver"));
        seg.add("Spleen, to do", findSegmentKind("spleen"));
        const fs::path file = fs::path(dir_.path().toStdString()) / "empty.dcm";
        QCOMPARE(writeSegmentationDicom(file, seg, series_).frames, std::size_t(2));
        const QStringList complaints = test::dciodvfyComplaints(file);
        QVERIFY2(complaints.isEmpty(), qPrintable(complaints.join('\n')));
        const ReadSegmentationDicom read = readSegmentationDicom(file, series_, ct_.geometry());
        QCOMPARE(read.segments.size(), std::size_t(2));
        QCOMPARE(read.segments[1].name, std::string("Spleen, to do"));
        QVERIFY(!read.segments[0].mask->any() && !read.segments[1].mask->any());
    }

    void readsBackEqual() {
        QVERIFY(fs::exists(written_));
        const Segmentation seg = test::segmentedCt(ct_);
        const ReadSegmentationDicom read = readSegmentationDicom(written_, series_, ct_.geometry());
        QVERIFY(read.header.writtenByLucent);
        QVERIFY(!read.readOnly);
        QCOMPARE(read.segments.size(), seg.segments().size());
        for (std::size_t i = 0; i < read.segments.size(); ++i) {
            const Segment& a = read.segments[i];
            const Segment& b = seg.segments()[i];
            QCOMPARE(read.segmentNumbers[i], std::uint16_t(i + 1));
            QCOMPARE(a.name, b.name);
            QVERIFY(a.category == b.category);
            QVERIFY2(a.type == b.type, a.type.meaning.c_str());
            QVERIFY2(a.colour == b.colour, b.name.c_str());
            QCOMPARE(a.algorithmType, b.algorithmType);
            QCOMPARE(a.algorithmName, b.algorithmName);
            QVERIFY2(*a.mask == *b.mask, b.name.c_str());
        }
        QVERIFY(!read.segments.back().mask->any()); // the empty one, still described

        // Into a document: the segments as they were, each one undo step.
        Segmentation again(ct_.geometry());
        const auto ids = addSegments(again, read.segments);
        QCOMPARE(ids.size(), seg.segments().size());
        for (std::size_t i = 0; i < ids.size(); ++i) {
            const Segment* s = again.find(ids[i]);
            QCOMPARE(s->algorithmType, seg.segments()[i].algorithmType);
            QCOMPARE(s->algorithmName, seg.segments()[i].algorithmName);
            QVERIFY(*s->mask == *seg.segments()[i].mask);
        }
    }

    void opensDcmqisLiverOnItsSlices() {
        REQUIRE_DATA(kDcmqi);
        const fs::path dir = test::kRealData / kDcmqi;
        const Volume ct = loadPath(dir);
        QCOMPARE(ct.dims(), glm::ivec3(512, 512, 3));
        const ReferencedSeries series =
            readReferencedSeries({dir / "01.dcm", dir / "02.dcm", dir / "03.dcm"});
        const ReadSegmentationDicom read =
            readSegmentationDicom(dir / "liver_seg.dcm", series, ct.geometry());
        QVERIFY(!read.header.writtenByLucent);
        QCOMPARE(read.segments.size(), std::size_t(1));
        const Segment& liver = read.segments.front();
        QCOMPARE(liver.name, std::string("Liver"));
        QCOMPARE(liver.type.value, std::string("T-62000")); // SRT, as dcmqi stored it
        QCOMPARE(liver.type.scheme, std::string("SRT"));
        QCOMPARE(liver.algorithmType, std::string("SEMIAUTOMATIC"));
        QCOMPARE(liver.algorithmName, std::string("SlicerEditor"));
        // Each frame's bits, decoded here, on the slice of the image it was derived from.
        const test::DecodedFrames frames = test::decodeBinaryFrames(dir / "liver_seg.dcm");
        QCOMPARE(frames.sources.size(), std::size_t(3));
        std::size_t expected = 0;
        for (std::size_t f = 0; f < frames.sources.size(); ++f) {
            const ReferencedImage* image = series.find(frames.sources[f]);
            QVERIFY(image != nullptr);
            const glm::dvec3 ijk = ct.geometry().toIndex(image->position);
            const int k = static_cast<int>(std::lround(ijk.z));
            QVERIFY(std::abs(ijk.x) < 1e-3 && std::abs(ijk.y) < 1e-3);
            std::size_t onSlice = 0;
            for (int j = 0; j < 512; ++j) {
                for (int i = 0; i < 512; ++i) {
                    const bool bit = frames.bit(f, i, j);
                    expected += bit;
                    onSlice += liver.mask->at(i, j, k);
                    if (bit != liver.mask->at(i, j, k)) {
                        QFAIL(qPrintable(QString("voxel %1 %2 %3").arg(i).arg(j).arg(k)));
                    }
                }
            }
            QVERIFY2(onSlice > 1000, "the liver covers a good part of each slice");
        }
        QCOMPARE(liver.mask->count(), expected);
    }

    // dcmjs, OHIF's library, as a second foreign writer: BINARY, and FRACTIONAL with RLE as
    // OHIF writes by default (read-only then).
    void opensDcmjsSegsOnTheirVoxels() {
        const Segmentation seg = test::segmentedCt(ct_);
        for (const bool rle : {false, true}) {
            QTemporaryDir dir;
            const test::DcmjsRun run =
                test::writeWithDcmjs(seg, series_, dir.path().toStdString(), rle);
            QVERIFY2(run.ok, run.message.c_str());
            const ReadSegmentationDicom read =
                readSegmentationDicom(run.file, series_, ct_.geometry());
            QVERIFY(!read.header.writtenByLucent);
            QCOMPARE(read.fractional, rle);
            QCOMPARE(read.readOnly, rle);
            QCOMPARE(read.notes.size(), std::size_t(rle ? 1 : 0)); // 0/1 under FRACTIONAL
            QCOMPARE(read.segments.size(), seg.segments().size());
            for (std::size_t i = 0; i < read.segments.size(); ++i) {
                const Segment& a = read.segments[i];
                const Segment& b = seg.segments()[i];
                QCOMPARE(a.name, b.name);
                QVERIFY(a.type == b.type);
                QVERIFY(a.category == b.category);
                QVERIFY2(a.colour == b.colour, b.name.c_str());
                QCOMPARE(a.algorithmType, b.algorithmType);
                const std::string difference = test::maskDifference(*a.mask, *b.mask);
                QVERIFY2(difference.empty(), (b.name + ": " + difference).c_str());
            }
        }
    }

    // FRACTIONAL: a voxel counts from half the maximum on (values below it do not).
    void readsFractionalAtHalfItsMaximum() {
        const fs::path fractional = fs::path(dir_.path().toStdString()) / "fractional.dcm";
        test::toFractional(written_, fractional);
        QVERIFY(!QTest::currentTestFailed());
        const ReadSegmentationDicom read =
            readSegmentationDicom(fractional, series_, ct_.geometry());
        QVERIFY(read.fractional && read.readOnly);
        QVERIFY(read.notes.empty());
        const Segmentation seg = test::segmentedCt(ct_);
        for (std::size_t i = 0; i < read.segments.size(); ++i) {
            const std::string difference =
                test::maskDifference(*read.segments[i].mask, *seg.segments()[i].mask);
            QVERIFY2(difference.empty(), (seg.segments()[i].name + ": " + difference).c_str());
        }
    }

    void brokenSegsNameTheFile() {
        QVERIFY(fs::exists(written_));
        const VolumeGeometry& grid = ct_.geometry();
        const fs::path dir = dir_.path().toStdString();

        const fs::path truncated = dir / "truncated.dcm";
        fs::copy_file(written_, truncated);
        fs::resize_file(truncated, fs::file_size(written_) * 2 / 3);
        std::string e = readError(truncated, series_, grid);
        QVERIFY2(e.find(truncated.string()) == 0, e.c_str());

        const fs::path headerOnly = dir / "header-only.dcm";
        fs::copy_file(written_, headerOnly);
        fs::resize_file(headerOnly, 2000);
        e = readError(headerOnly, series_, grid);
        QVERIFY2(e.find(headerOnly.string()) == 0, e.c_str());

        const fs::path garbage = dir / "garbage.dcm";
        std::ofstream(garbage) << std::string(5000, 'x');
        e = readError(garbage, series_, grid);
        QVERIFY2(e.find(garbage.string()) == 0 && e.find("not a readable DICOM") != e.npos,
                 e.c_str());

        const fs::path ct = series_.images.front().file;
        e = readError(ct, series_, grid);
        QVERIFY2(e.find(ct.string()) == 0 && e.find("not a DICOM Segmentation") != e.npos,
                 e.c_str());
        e = readError(dir / "absent.dcm", series_, grid);
        QVERIFY2(e.find("absent.dcm: no such file") != e.npos, e.c_str());

        // dcmqi's liver refers to images of another series.
        REQUIRE_DATA(kDcmqi);
        const fs::path liver = test::kRealData / kDcmqi / "liver_seg.dcm";
        e = readError(liver, series_, grid);
        QVERIFY2(e.find(liver.string()) == 0 &&
                     e.find("not in series " + series_.seriesUid) != e.npos,
                 e.c_str());

        // Frames on another orientation (the sources dropped so the planes decide).
        const fs::path tilted = dir / "tilted.dcm";
        test::rewriteFrames(written_, tilted, "0\\1\\0\\0\\0\\-1");
        QVERIFY(!QTest::currentTestFailed());
        e = readError(tilted, series_, grid);
        QVERIFY2(e.find(tilted.string()) == 0 && e.find("not oriented as") != e.npos, e.c_str());
    }

    // dcmqi's liver SEG damaged at random (a fixed seed) all through its header, functional
    // groups and frames: each copy reads or is refused naming the file, never anything else.
    void damagedCopiesReadOrAreNamed() {
        REQUIRE_DATA(kDcmqi);
        const fs::path dir = test::kRealData / kDcmqi;
        const Volume ct = loadPath(dir);
        const ReferencedSeries series =
            readReferencedSeries({dir / "01.dcm", dir / "02.dcm", dir / "03.dcm"});
        std::ifstream in(dir / "liver_seg.dcm", std::ios::binary);
        const std::string original((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
        std::mt19937 random(30);
        int refused = 0;
        for (int copy = 0; copy < 60; ++copy) {
            std::string bytes = original;
            for (int n = 0; n < 8; ++n) {
                const std::size_t at = 132 + random() % (bytes.size() - 132);
                bytes[at] = static_cast<char>(random() % 256);
            }
            const fs::path file =
                fs::path(dir_.path().toStdString()) / ("damaged" + std::to_string(copy) + ".dcm");
            std::ofstream(file, std::ios::binary) << bytes;
            try {
                readSegmentationDicom(file, series, ct.geometry());
            } catch (const SegmentationDicomError& e) {
                QVERIFY2(std::string(e.what()).find(file.string()) == 0, e.what());
                ++refused;
            }
        }
        qInfo("%d of 60 damaged copies refused, the others read", refused);
    }

    void framesWithoutSourcesGoByPosition() {
        const fs::path plain = fs::path(dir_.path().toStdString()) / "by-position.dcm";
        test::rewriteFrames(written_, plain, "");
        QVERIFY(!QTest::currentTestFailed());
        const ReadSegmentationDicom read = readSegmentationDicom(plain, series_, ct_.geometry());
        const Segmentation seg = test::segmentedCt(ct_);
        for (std::size_t i = 0; i < read.segments.size(); ++i) {
            QVERIFY2(*read.segments[i].mask == *seg.segments()[i].mask,
                     seg.segments()[i].name.c_str());
        }
    }

    void writingNamesTheFileOnFailure() {
        const Segmentation seg = test::segmentedCt(ct_);
        const fs::path nowhere = "/proc/no-such-dir/seg.dcm";
        try {
            writeSegmentationDicom(nowhere, seg, series_);
            QFAIL("written where no file can be");
        } catch (const SegmentationDicomError& e) {
            QVERIFY2(std::string(e.what()).find(nowhere.string()) != std::string::npos, e.what());
        }
        // A series that is not the segments' grid: named too.
        ReferencedSeries three = series_;
        three.images.resize(3);
        try {
            writeSegmentationDicom(written_.parent_path() / "short.dcm", seg, three);
            QFAIL("written without the slices' images");
        } catch (const SegmentationDicomError& e) {
            QVERIFY2(std::string(e.what()).find("short.dcm: slice ") != std::string::npos,
                     e.what());
        }
    }
};

QTEST_GUILESS_MAIN(TestSegmentationDicom)
#include "test_segmentation_dicom.moc"
