#pragma once
// A SEG file as another reader sees it: its attributes and frames read with dcmdata alone
// (not with Lucent's reader), dciodvfy's verdict, and copies with frames changed.

#include <QProcess>
#include <QStringList>
#include <QTest>

#include <filesystem>
#include <string>
#include <vector>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include "core/report/ReferencedSeries.h"
#include "core/segmentation/Segmentation.h"

namespace lucent::test {

// dciodvfy's error lines ("Error - ...") and its warnings but the tolerated ones, or a line
// saying it could not run. Tolerated: the source CT's Patient Name "HEAD", copied as it is
// ("Retired Person Name form").
inline QStringList dciodvfyComplaints(const std::filesystem::path& file) {
    QProcess p;
    p.setProcessChannelMode(QProcess::MergedChannels);
    p.start("dciodvfy", {QString::fromStdString(file.string())});
    if (!p.waitForStarted(10000)) {
        return {"dciodvfy did not start: install dicom3tools (packaging/install-deps.sh)"};
    }
    p.waitForFinished(120000);
    const QStringList tolerated = {"Retired Person Name form"};
    QStringList complaints;
    for (const QString& line : QString::fromUtf8(p.readAll()).split('\n')) {
        const bool named = std::any_of(tolerated.begin(), tolerated.end(),
                                       [&](const QString& t) { return line.contains(t); });
        if (line.startsWith("Error") || (line.startsWith("Warning") && !named)) {
            complaints << line;
        }
    }
    return complaints;
}

// The slices of each segment that hold a voxel: the frames a SEG of them has.
inline std::size_t nonEmptySlices(const Segmentation& seg) {
    std::size_t n = 0;
    const glm::ivec3 d = seg.geometry().dims;
    for (const Segment& s : seg.segments()) {
        for (int k = 0; k < d.z; ++k) {
            bool any = false;
            for (int j = 0; j < d.y && !any; ++j) {
                for (int i = 0; i < d.x && !any; ++i) {
                    any = s.mask->at(i, j, k);
                }
            }
            n += any;
        }
    }
    return n;
}

inline std::string str(DcmItem& d, const DcmTagKey& tag) {
    OFString v;
    d.findAndGetOFStringArray(tag, v);
    return v.c_str();
}

// "" when equal, else the counts and the first voxel that differs.
inline std::string maskDifference(const SegmentMask& a, const SegmentMask& b) {
    if (a == b) {
        return {};
    }
    std::string text = "voxels " + std::to_string(a.count()) + " vs " + std::to_string(b.count());
    for (std::size_t n = 0; n < a.size() && n < b.size(); ++n) {
        if (a.get(n) != b.get(n)) {
            const glm::ivec3 v = a.voxelOf(n);
            return text + ", first at " + std::to_string(v.x) + " " + std::to_string(v.y) + " " +
                   std::to_string(v.z);
        }
    }
    return text;
}

// Every frame of a BINARY SEG: its segment, its first source image, its bits.
struct DecodedFrames {
    int rows = 0;
    int columns = 0;
    std::vector<int> segments;
    std::vector<std::string> sources;
    std::vector<std::vector<double>> positions;
    std::vector<std::vector<Uint32>> indices; // DimensionIndexValues
    std::vector<Uint8> bits;
    bool bit(std::size_t frame, int i, int j) const {
        const std::size_t b = frame * rows * columns + static_cast<std::size_t>(j) * columns + i;
        return (bits[b >> 3] >> (b & 7)) & 1u;
    }
};

inline DecodedFrames decodeBinaryFrames(const std::filesystem::path& file) {
    DecodedFrames out;
    DcmFileFormat f;
    if (f.loadFile(file.c_str()).bad()) {
        return out;
    }
    DcmDataset& d = *f.getDataset();
    Uint16 rows = 0, columns = 0;
    d.findAndGetUint16(DCM_Rows, rows);
    d.findAndGetUint16(DCM_Columns, columns);
    out.rows = rows;
    out.columns = columns;
    DcmSequenceOfItems* frames = nullptr;
    d.findAndGetSequence(DCM_PerFrameFunctionalGroupsSequence, frames);
    for (unsigned long n = 0; frames != nullptr && n < frames->card(); ++n) {
        DcmItem* frame = frames->getItem(n);
        DcmItem* id = nullptr;
        DcmItem* derivation = nullptr;
        DcmItem* source = nullptr;
        DcmItem* position = nullptr;
        DcmItem* content = nullptr;
        Uint16 segment = 0;
        if (frame->findAndGetSequenceItem(DCM_SegmentIdentificationSequence, id).good()) {
            id->findAndGetUint16(DCM_ReferencedSegmentNumber, segment);
        }
        out.segments.push_back(segment);
        std::string uid;
        if (frame->findAndGetSequenceItem(DCM_DerivationImageSequence, derivation).good() &&
            derivation->findAndGetSequenceItem(DCM_SourceImageSequence, source).good()) {
            uid = str(*source, DCM_ReferencedSOPInstanceUID);
        }
        out.sources.push_back(uid);
        std::vector<double> p(3, 0.0);
        if (frame->findAndGetSequenceItem(DCM_PlanePositionSequence, position).good()) {
            for (unsigned long c = 0; c < 3; ++c) {
                position->findAndGetFloat64(DCM_ImagePositionPatient, p[c], c);
            }
        }
        out.positions.push_back(p);
        std::vector<Uint32> index(2, 0);
        if (frame->findAndGetSequenceItem(DCM_FrameContentSequence, content).good()) {
            for (unsigned long c = 0; c < 2; ++c) {
                content->findAndGetUint32(DCM_DimensionIndexValues, index[c], c);
            }
        }
        out.indices.push_back(index);
    }
    const Uint8* pixels = nullptr;
    unsigned long count = 0;
    if (d.findAndGetUint8Array(DCM_PixelData, pixels, &count).good()) {
        out.bits.assign(pixels, pixels + count);
    }
    return out;
}

// Checks, with dcmdata alone, what Lucent's SEG of `seg` on `series` must say.
inline void checkSegFile(const std::filesystem::path& file, const Segmentation& seg,
                         const ReferencedSeries& series, const VolumeGeometry& grid) {
    DcmFileFormat f;
    QVERIFY(f.loadFile(file.c_str()).good());
    DcmDataset& d = *f.getDataset();
    QCOMPARE(str(d, DCM_SOPClassUID), std::string("1.2.840.10008.5.1.4.1.1.66.4"));
    QCOMPARE(str(d, DCM_Modality), std::string("SEG"));
    QCOMPARE(str(d, DCM_SegmentationType), std::string("BINARY"));
    QCOMPARE(str(d, DCM_Manufacturer), std::string("Lucent"));
    QCOMPARE(str(d, DCM_StudyInstanceUID), series.studyUid);
    QCOMPARE(str(d, DCM_FrameOfReferenceUID), series.frameOfReferenceUid);
    QVERIFY(str(d, DCM_SeriesInstanceUID) != series.seriesUid);
    DcmFileFormat source;
    QVERIFY(source.loadFile(series.images.front().file.c_str()).good());
    QCOMPARE(str(d, DCM_PatientID), str(*source.getDataset(), DCM_PatientID));
    QCOMPARE(str(d, DCM_PatientName), str(*source.getDataset(), DCM_PatientName));
    DcmSequenceOfItems* segments = nullptr;
    QVERIFY(d.findAndGetSequence(DCM_SegmentSequence, segments).good());
    QCOMPARE(std::size_t(segments->card()), seg.segments().size());
    for (unsigned long n = 0; n < segments->card(); ++n) {
        DcmItem& s = *segments->getItem(n);
        const Segment& expected = seg.segments()[n];
        Uint16 number = 0;
        s.findAndGetUint16(DCM_SegmentNumber, number);
        QCOMPARE(number, Uint16(n + 1));
        QCOMPARE(str(s, DCM_SegmentLabel), expected.name);
        QCOMPARE(str(s, DCM_SegmentAlgorithmType), expected.algorithmType);
        QCOMPARE(str(s, DCM_SegmentAlgorithmName),
                 expected.algorithmType == "MANUAL" ? std::string() : expected.algorithmName);
        QVERIFY(s.tagExists(DCM_RecommendedDisplayCIELabValue));
    }
    const DecodedFrames frames = decodeBinaryFrames(file);
    QCOMPARE(frames.rows, grid.dims.y);
    QCOMPARE(frames.columns, grid.dims.x);
    for (std::size_t n = 0; n < frames.segments.size(); ++n) {
        const ReferencedImage* image = series.find(frames.sources[n]);
        QVERIFY2(image != nullptr, "each frame's source image is a slice of the series");
        const glm::dvec3 p(frames.positions[n][0], frames.positions[n][1], frames.positions[n][2]);
        QVERIFY(glm::length(p - image->position) < 1e-3);
        const int k = static_cast<int>(std::lround(grid.toIndex(image->position).z));
        QCOMPARE(frames.indices[n][0], Uint32(frames.segments[n]));
        QCOMPARE(frames.indices[n][1], Uint32(k + 1));
        const SegmentMask& mask = *seg.segments()[frames.segments[n] - 1].mask;
        for (int j = 0; j < grid.dims.y; ++j) {
            for (int i = 0; i < grid.dims.x; ++i) {
                if (frames.bit(n, i, j) != mask.at(i, j, k)) {
                    QFAIL(qPrintable(QString("frame %1 pixel %2 %3").arg(n).arg(i).arg(j)));
                }
            }
        }
    }
}

// A copy of a SEG whose frames lost their source images (the plane positions decide), with
// the shared orientation replaced when `orientation` is given.
inline void rewriteFrames(const std::filesystem::path& in, const std::filesystem::path& out,
                          const char* orientation) {
    DcmFileFormat f;
    QVERIFY(f.loadFile(in.c_str()).good());
    DcmDataset& d = *f.getDataset();
    DcmSequenceOfItems* frames = nullptr;
    QVERIFY(d.findAndGetSequence(DCM_PerFrameFunctionalGroupsSequence, frames).good());
    for (unsigned long n = 0; n < frames->card(); ++n) {
        delete frames->getItem(n)->remove(DCM_DerivationImageSequence);
    }
    if (*orientation != '\0') {
        DcmItem* shared = nullptr;
        DcmItem* plane = nullptr;
        QVERIFY(d.findAndGetSequenceItem(DCM_SharedFunctionalGroupsSequence, shared).good());
        QVERIFY(shared->findAndGetSequenceItem(DCM_PlaneOrientationSequence, plane).good());
        QVERIFY(plane->putAndInsertString(DCM_ImageOrientationPatient, orientation).good());
    }
    QVERIFY(f.saveFile(out.c_str(), EXS_LittleEndianExplicit).good());
}

// A FRACTIONAL copy of a BINARY SEG (maximum 255): set pixels 128..255, unset ones 0..127.
inline void toFractional(const std::filesystem::path& in, const std::filesystem::path& out) {
    const DecodedFrames frames = decodeBinaryFrames(in);
    DcmFileFormat f;
    QVERIFY(f.loadFile(in.c_str()).good());
    DcmDataset& d = *f.getDataset();
    const std::size_t plane = static_cast<std::size_t>(frames.rows) * frames.columns;
    std::vector<Uint8> values(plane * frames.segments.size());
    for (std::size_t n = 0; n < values.size(); ++n) {
        const bool set = (frames.bits[n >> 3] >> (n & 7)) & 1u;
        values[n] = static_cast<Uint8>(set ? 128 + n % 128 : n % 128);
    }
    QVERIFY(d.putAndInsertUint8Array(DCM_PixelData, values.data(), values.size()).good());
    QVERIFY(d.putAndInsertUint16(DCM_BitsAllocated, 8).good());
    QVERIFY(d.putAndInsertUint16(DCM_BitsStored, 8).good());
    QVERIFY(d.putAndInsertUint16(DCM_HighBit, 7).good());
    QVERIFY(d.putAndInsertString(DCM_SegmentationType, "FRACTIONAL").good());
    QVERIFY(d.putAndInsertString(DCM_SegmentationFractionalType, "PROBABILITY").good());
    QVERIFY(d.putAndInsertUint16(DCM_MaximumFractionalValue, 255).good());
    QVERIFY(f.saveFile(out.c_str(), EXS_LittleEndianExplicit).good());
}

} // namespace lucent::test
