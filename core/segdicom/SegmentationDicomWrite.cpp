// Writing segments as a DICOM SEG with DCMTK's dcmseg (BINARY): the frames come straight from
// the bit masks, one slice at a time; the per-slice functional groups are built once and
// shared by every segment's frame on that slice (dcmseg copies them per frame).
#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <memory>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcostrmb.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmfg/fgderimg.h>
#include <dcmtk/dcmfg/fgfracon.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmiod/cielabutil.h>
#include <dcmtk/dcmiod/iodreferences.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include "core/formats/AtomicFile.h"
#include "core/report/MeasurementReport.h" // kLucentManufacturer
#include "core/segdicom/SegmentationDicom.h"
#include "core/segdicom/SliceImages_p.h"

namespace lucent {

namespace fs = std::filesystem;

namespace {

void check(const OFCondition& c, const fs::path& file, const std::string& what) {
    if (c.bad()) {
        throw SegmentationDicomError(file.string() + ": " + what + ": " + c.text());
    }
}

std::string newUid() {
    char buffer[100];
    return dcmGenerateUniqueIdentifier(buffer, SITE_INSTANCE_UID_ROOT);
}

// A DS value: at most 16 characters, as close to v as fits.
std::string decimal(double v) {
    char text[32];
    for (int digits = 15; digits > 0; --digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, v);
        if (std::string(text).size() <= 16) {
            break;
        }
    }
    return text;
}

DcmSegTypes::E_SegmentAlgoType algorithmType(const std::string& type) {
    if (type == "AUTOMATIC") {
        return DcmSegTypes::SAT_AUTOMATIC;
    }
    return type == "SEMIAUTOMATIC" ? DcmSegTypes::SAT_SEMIAUTOMATIC : DcmSegTypes::SAT_MANUAL;
}

// LO: at most 64 characters, no backslash.
std::string longString(std::string text, const std::string& fallback) {
    std::replace(text.begin(), text.end(), '\\', '/');
    if (text.size() > 64) {
        text.resize(64);
    }
    return text.empty() ? fallback : text;
}

CodeSequenceMacro codeOf(const CodedConcept& c) {
    return CodeSequenceMacro(c.value.c_str(), c.scheme.c_str(), longString(c.meaning, "?").c_str());
}

void addSegmentDescription(DcmSegmentation& seg, const Segment& s, std::size_t index,
                           const fs::path& file) {
    const std::string label = longString(s.name, "Segment " + std::to_string(index + 1));
    const DcmSegTypes::E_SegmentAlgoType type = algorithmType(s.algorithmType);
    // With ASCII placeholders for the texts: DCMTK checks LO values against ASCII alone, and
    // the names are UTF-8; setTexts() puts them into the dataset.
    DcmSegment* created = nullptr;
    check(DcmSegment::create(created, "Segment", codeOf(s.category), codeOf(s.type), type,
                             type == DcmSegTypes::SAT_MANUAL ? "" : "Lucent"),
          file, "segment " + label);
    std::unique_ptr<DcmSegment> segment(created);
    double l = 0.0, a = 0.0, b = 0.0;
    IODCIELabUtil::rgb2DicomLab(l, a, b, s.colour[0] / 255.0, s.colour[1] / 255.0,
                                s.colour[2] / 255.0);
    const auto u16 = [](double v) {
        return static_cast<Uint16>(std::clamp(v + 0.5, 0.0, 65535.0));
    };
    check(segment->setRecommendedDisplayCIELabValue(u16(l), u16(a), u16(b)), file,
          "colour of segment " + label);
    Uint16 number = 0;
    check(seg.addSegment(segment.get(), number), file, "segment " + label);
    segment.release(); // the document owns it now
    if (number != index + 1) {
        throw SegmentationDicomError(file.string() + ": segment " + label + " got number " +
                                     std::to_string(number));
    }
}

// Each segment's label and algorithm name into the written Segment Sequence, as UTF-8.
void setTexts(DcmDataset& dataset, const std::vector<Segment>& segments, const fs::path& file) {
    DcmSequenceOfItems* sequence = nullptr;
    check(dataset.findAndGetSequence(DCM_SegmentSequence, sequence), file, "Segment Sequence");
    for (unsigned long n = 0; n < sequence->card() && n < segments.size(); ++n) {
        DcmItem& item = *sequence->getItem(n);
        const Segment& s = segments[n];
        check(item.putAndInsertString(
                  DCM_SegmentLabel, longString(s.name, "Segment " + std::to_string(n + 1)).c_str()),
              file, "segment label");
        if (algorithmType(s.algorithmType) != DcmSegTypes::SAT_MANUAL) {
            check(item.putAndInsertString(DCM_SegmentAlgorithmName,
                                          longString(s.algorithmName, "Lucent").c_str()),
                  file, "segment algorithm");
        }
    }
}

// What every frame shares: the pixel size, the orientation, the dimensions.
void addSharedGroups(DcmSegmentation& seg, const VolumeGeometry& grid, const fs::path& file) {
    FGPixelMeasures measures;
    check(measures.setPixelSpacing(
              (decimal(grid.spacing.y) + "\\" + decimal(grid.spacing.x)).c_str()),
          file, "pixel spacing");
    check(measures.setSliceThickness(decimal(grid.spacing.z).c_str()), file, "slice thickness");
    check(measures.setSpacingBetweenSlices(decimal(grid.spacing.z).c_str()), file,
          "spacing between slices");
    check(seg.addForAllFrames(measures), file, "pixel measures");
    const glm::dvec3 r = glm::normalize(grid.direction[0]);
    const glm::dvec3 c = glm::normalize(grid.direction[1]);
    const std::unique_ptr<FGPlaneOrientationPatient> orientation(
        FGPlaneOrientationPatient::createMinimal(decimal(r.x).c_str(), decimal(r.y).c_str(),
                                                 decimal(r.z).c_str(), decimal(c.x).c_str(),
                                                 decimal(c.y).c_str(), decimal(c.z).c_str()));
    if (!orientation) {
        throw SegmentationDicomError(file.string() + ": plane orientation");
    }
    check(seg.addForAllFrames(*orientation), file, "plane orientation");
    const std::string dimensions = newUid();
    check(seg.getDimensions().addDimensionIndex(DCM_ReferencedSegmentNumber, dimensions.c_str(),
                                                DCM_SegmentIdentificationSequence,
                                                "ReferencedSegmentNumber"),
          file, "dimension index");
    check(seg.getDimensions().addDimensionIndex(DCM_ImagePositionPatient, dimensions.c_str(),
                                                DCM_PlanePositionSequence, "ImagePositionPatient"),
          file, "dimension index");
}

// One slice's plane position and derivation (from its source image), built once.
struct SliceGroups {
    std::unique_ptr<FGPlanePosPatient> position;
    std::unique_ptr<FGDerivationImage> derivation;
};

SliceGroups sliceGroups(const VolumeGeometry& grid, int k, const ReferencedImage& image,
                        const fs::path& file) {
    const glm::dvec3 p = grid.toPatient({0.0, 0.0, static_cast<double>(k)});
    SliceGroups g;
    g.position.reset(FGPlanePosPatient::createMinimal(decimal(p.x).c_str(), decimal(p.y).c_str(),
                                                      decimal(p.z).c_str()));
    ImageSOPInstanceReferenceMacro source;
    check(source.setReferencedSOPClassUID(image.sopClassUid.c_str()), file,
          "source image class of " + image.file.string());
    check(source.setReferencedSOPInstanceUID(image.sopInstanceUid.c_str()), file,
          "source image of " + image.file.string());
    OFVector<ImageSOPInstanceReferenceMacro> sources;
    sources.push_back(source);
    g.derivation.reset(FGDerivationImage::createMinimal(
        sources, "Segmentation", CodeSequenceMacro("113076", "DCM", "Segmentation"),
        CodeSequenceMacro("121322", "DCM", "Source image for image processing operation")));
    if (!g.position || !g.derivation) {
        throw SegmentationDicomError(file.string() + ": functional groups of slice " +
                                     std::to_string(k));
    }
    return g;
}

// True when slice k of the mask holds a voxel.
bool sliceAny(const SegmentMask& mask, int k) {
    const std::size_t plane = static_cast<std::size_t>(mask.dims().x) * mask.dims().y;
    const std::size_t first = plane * static_cast<std::size_t>(k);
    const std::span<const std::uint64_t> words = mask.words();
    for (std::size_t n = 0; n < plane;) {
        const std::size_t index = first + n;
        const std::size_t take = std::min<std::size_t>(64 - (index & 63), plane - n);
        const std::uint64_t bits = words[index >> 6] >> (index & 63);
        if ((take == 64 ? bits : bits & ((std::uint64_t{1} << take) - 1)) != 0) {
            return true;
        }
        n += take;
    }
    return false;
}

// The BINARY Pixel Data: frames of 1 bit per pixel, the low bit first, packed with no padding
// between frames. A mask's bits lie in the same order (i fastest, then j), so a slice whose
// first bit falls on a byte is copied as bytes.
struct PackedFrames {
    std::vector<Uint8> bytes;
    std::size_t bits = 0;

    void append(const SegmentMask& mask, int k) {
        const std::size_t plane = static_cast<std::size_t>(mask.dims().x) * mask.dims().y;
        const std::size_t first = plane * static_cast<std::size_t>(k);
        bytes.resize((bits + plane + 7) / 8, 0);
        std::size_t done = 0;
        if constexpr (std::endian::native == std::endian::little) {
            if ((bits & 7) == 0 && (first & 7) == 0) {
                const auto* source = reinterpret_cast<const Uint8*>(mask.words().data());
                std::memcpy(bytes.data() + bits / 8, source + first / 8, plane / 8);
                done = plane / 8 * 8;
            }
        }
        for (; done < plane; ++done) {
            if (mask.get(first + done)) {
                const std::size_t b = bits + done;
                bytes[b >> 3] = static_cast<Uint8>(bytes[b >> 3] | (1u << (b & 7)));
            }
        }
        bits += plane;
    }
};

// The frames of every segment on every slice where it has a voxel, by segment then slice:
// their functional groups go to dcmseg, their pixels to `packed`. dcmseg's frames stay one
// pixel each: 3.6.7 takes a frame one byte per pixel and packs it pixel by pixel, most of the
// writing time; the packed frames replace its Pixel Data afterwards.
std::size_t addFrames(DcmSegmentation& seg, const Segmentation& segmentation,
                      const std::vector<const ReferencedImage*>& slices, PackedFrames& packed,
                      const fs::path& file) {
    const VolumeGeometry& grid = segmentation.geometry();
    std::vector<SliceGroups> groups(slices.size());
    Uint8 onePixel = 0;
    std::size_t frames = 0;
    const auto addFrame = [&](std::size_t s, int k) {
        SliceGroups& g = groups[static_cast<std::size_t>(k)];
        if (!g.position) {
            g = sliceGroups(grid, k, *slices[static_cast<std::size_t>(k)], file);
        }
        FGFrameContent content;
        check(content.setDimensionIndexValues(static_cast<Uint32>(s + 1), 0), file, "frame index");
        check(content.setDimensionIndexValues(static_cast<Uint32>(k + 1), 1), file, "frame index");
        OFVector<FGBase*> perFrame;
        perFrame.push_back(g.position.get());
        perFrame.push_back(g.derivation.get());
        perFrame.push_back(&content);
        check(seg.addFrame(&onePixel, static_cast<Uint16>(s + 1), perFrame), file,
              "frame of segment " + std::to_string(s + 1) + " on slice " + std::to_string(k));
        packed.append(*segmentation.segments()[s].mask, k);
        ++frames;
    };
    const std::vector<Segment>& segments = segmentation.segments();
    std::vector<std::pair<std::size_t, int>> placed; // (segment, slice), in frame order
    std::vector<bool> hasFrame(segments.size(), false);
    for (std::size_t s = 0; s < segments.size(); ++s) {
        for (int k = 0; k < grid.dims.z; ++k) {
            if (sliceAny(*segments[s].mask, k)) {
                placed.emplace_back(s, k);
                hasFrame[s] = true;
            }
        }
    }
    // dcmseg 3.6.7 refuses fewer frames than segments: then each empty segment gets one empty
    // frame on the first slice (else empty frames are left out).
    if (placed.size() < segments.size()) {
        for (std::size_t s = 0; s < segments.size(); ++s) {
            if (!hasFrame[s]) {
                placed.emplace_back(s, 0);
            }
        }
        std::sort(placed.begin(), placed.end());
    }
    for (const auto& [s, k] : placed) {
        addFrame(s, k);
    }
    return frames;
}

// The frames' real size and pixels into the written dataset (see addFrames).
void setPixelData(DcmDataset& dataset, const VolumeGeometry& grid, const PackedFrames& packed,
                  const fs::path& file) {
    check(dataset.putAndInsertUint16(DCM_Rows, static_cast<Uint16>(grid.dims.y)), file, "rows");
    check(dataset.putAndInsertUint16(DCM_Columns, static_cast<Uint16>(grid.dims.x)), file,
          "columns");
    if (packed.bytes.size() >= 0xFFFFFFFEu) {
        throw SegmentationDicomError(file.string() + ": more than 4 GB of frames");
    }
    // Even length, as DICOM wants: dcmdata pads odd OB values with a zero byte itself.
    check(dataset.putAndInsertUint8Array(DCM_PixelData, packed.bytes.data(),
                                         static_cast<unsigned long>(packed.bytes.size())),
          file, "pixel data");
}

// The source series as the Common Instance Reference module names it.
void addReferences(DcmSegmentation& seg, const ReferencedSeries& source,
                   const std::vector<const ReferencedImage*>& slices,
                   const std::string& patientId) {
    IODReferences references;
    for (const ReferencedImage* image : slices) {
        references.add(new IODImageReference(
            patientId.c_str(), source.studyUid.c_str(), source.seriesUid.c_str(),
            image->sopInstanceUid.c_str(), image->sopClassUid.c_str()));
    }
    seg.getCommonInstanceReference().addReferences(references, source.studyUid.c_str());
}

// The dataset as a file, whole or not at all. The temporary name keeps the target's as its
// start: a study store's temporary file names its writer's process, and the store keeps such
// files while that process runs.
void saveWhole(DcmFileFormat& format, const fs::path& file) {
    try {
        formats::AtomicFileWriter writer(file,
                                         file.parent_path() / (file.filename().string() + ".part"));
        std::vector<char> buffer(1 << 20);
        DcmOutputBufferStream out(buffer.data(), buffer.size());
        format.transferInit();
        OFCondition c = EC_Normal;
        void* chunk = nullptr;
        offile_off_t length = 0;
        do {
            c = format.write(out, EXS_LittleEndianExplicit, EET_ExplicitLength, nullptr);
            out.flushBuffer(chunk, length);
            writer.stream().write(static_cast<const char*>(chunk),
                                  static_cast<std::streamsize>(length));
        } while (c == EC_StreamNotifyClient);
        format.transferEnd();
        if (c.bad()) {
            throw SegmentationDicomError(file.string() + ": cannot encode the SEG: " + c.text());
        }
        writer.commit();
    } catch (const SegmentationDicomError&) {
        throw;
    } catch (const std::runtime_error& e) { // AtomicFileWriter's, naming the file
        throw SegmentationDicomError(e.what());
    }
}

bool ascii(const std::string& text) {
    return std::all_of(text.begin(), text.end(),
                       [](char c) { return static_cast<unsigned char>(c) < 0x80; });
}

} // namespace

WrittenSegmentation writeSegmentationDicom(const fs::path& file, const Segmentation& segmentation,
                                           const ReferencedSeries& source,
                                           const SegmentationIdentity& identity) {
    const VolumeGeometry& grid = segmentation.geometry();
    if (segmentation.segments().empty()) {
        throw SegmentationDicomError(file.string() + ": no segment to write");
    }
    if (grid.dims.x <= 0 || grid.dims.y <= 0 || grid.dims.x > 65535 || grid.dims.y > 65535) {
        throw SegmentationDicomError(file.string() + ": the grid's slices cannot be DICOM frames");
    }
    const std::vector<const ReferencedImage*> slices = segdicom::imagesBySlice(source, grid);
    for (std::size_t k = 0; k < slices.size(); ++k) {
        if (slices[k] == nullptr) {
            throw SegmentationDicomError(file.string() + ": slice " + std::to_string(k) +
                                         " of the segments' grid is no image of series " +
                                         source.seriesUid);
        }
    }
    DcmFileFormat first;
    const fs::path& firstFile = slices.front()->file;
    if (first.loadFile(firstFile.c_str(), EXS_Unknown, EGL_noChange, 256).bad()) {
        throw SegmentationDicomError(firstFile.string() + ": cannot read the series' image");
    }
    const bool utf8 = std::any_of(segmentation.segments().begin(), segmentation.segments().end(),
                                  [](const Segment& s) { return !ascii(s.name); });
    if (utf8) { // the names are UTF-8: so is the whole SEG
        check(first.convertToUTF8(), file, "character set of " + firstFile.string());
    }
    DcmSegmentation* created = nullptr;
    check(DcmSegmentation::createBinarySegmentation(
              created, 1, 1, // frames of one pixel: see addFrames
              IODGeneralEquipmentModule::EquipmentInfo(kLucentManufacturer, "Lucent", "1",
                                                       identity.softwareVersion.c_str()),
              ContentIdentificationMacro("1", "SEGMENTATION", "Lucent segmentation", "")),
          file, "new segmentation");
    const std::unique_ptr<DcmSegmentation> seg(created);
    // Its check of every frame's groups walks a map per frame per group (a fifth of the
    // writing); the groups are built here the same way for every frame, and the tests check
    // the files with dciodvfy. Its dimension check runs before the per-frame groups exist.
    seg->setCheckFGOnWrite(OFFalse);
    seg->setCheckDimensionsOnWrite(OFFalse);
    check(seg->importFromSourceImage(*first.getDataset()), file,
          "patient and study of " + firstFile.string());
    const std::string seriesUid = identity.seriesUid.empty() ? newUid() : identity.seriesUid;
    const std::string sopUid = newUid();
    check(seg->getSeries().setSeriesInstanceUID(seriesUid.c_str()), file, "series UID");
    check(seg->getSeries().setSeriesNumber(std::to_string(identity.seriesNumber).c_str()), file,
          "series number");
    check(seg->getSeries().setSeriesDescription(
              longString(identity.seriesDescription, "Segmentation").c_str()),
          file, "series description");
    check(seg->getSOPCommon().setSOPInstanceUID(sopUid.c_str()), file, "SOP instance UID");
    for (std::size_t s = 0; s < segmentation.segments().size(); ++s) {
        addSegmentDescription(*seg, segmentation.segments()[s], s, file);
    }
    addSharedGroups(*seg, grid, file);
    WrittenSegmentation written;
    PackedFrames packed;
    written.frames = addFrames(*seg, segmentation, slices, packed, file);
    OFString patientId;
    first.getDataset()->findAndGetOFString(DCM_PatientID, patientId);
    addReferences(*seg, source, slices, patientId.c_str());

    DcmFileFormat out;
    DcmDataset& dataset = *out.getDataset();
    check(seg->writeDataset(dataset), file, "SEG dataset");
    setTexts(dataset, segmentation.segments(), file);
    setPixelData(dataset, grid, packed, file);
    if (utf8) {
        check(dataset.putAndInsertString(DCM_SpecificCharacterSet, "ISO_IR 192"), file,
              "character set");
    }
    saveWhole(out, file);
    written.sopInstanceUid = sopUid;
    written.seriesUid = seriesUid;
    written.studyUid = source.studyUid;
    return written;
}

} // namespace lucent
