// Header reading for one DICOM file with GDCM: classic single-frame images,
// legacy multi-frame, and Enhanced CT/MR with per-frame functional groups.
#include "core/dicom/DataSetStream_p.h"
#include "core/dicom/DicomStructure.h"
#include "core/dicom/DicomTags_p.h"
#include "core/dicom/ImageRecord.h"
#include "core/io/LoadControl.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>

#include <gdcmMediaStorage.h>
#include <gdcmReader.h>
#include <gdcmSequenceOfItems.h>
#include <gdcmTrace.h>

namespace lucent {
namespace {

namespace fs = std::filesystem;

const gdcm::Tag kPixelData(0x7fe0, 0x0010);
const std::string kExplicitLE = "1.2.840.10008.1.2.1";
const std::string kImplicitLE = "1.2.840.10008.1.2";
const std::string kDeflated = "1.2.840.10008.1.2.1.99";

// Lucent reports problems itself; GDCM's own messages on stderr would only confuse.
void quietGdcm() {
    static std::once_flag once;
    std::call_once(once, [] {
        gdcm::Trace::SetWarning(false);
        gdcm::Trace::SetDebug(false);
        gdcm::Trace::SetError(false);
    });
}
const gdcm::Tag kPerFrameGroups(0x5200, 0x9230);

// Classic, per-file attributes common to every frame.
void readCommon(const gdcm::DataSet& ds, ImageRecord& r) {
    r.sopClassUid = tagString(ds, 0x0008, 0x0016);
    r.sopInstanceUid = tagString(ds, 0x0008, 0x0018);
    r.seriesUid = tagString(ds, 0x0020, 0x000e);
    r.studyUid = tagString(ds, 0x0020, 0x000d);
    r.modality = tagString(ds, 0x0008, 0x0060);
    r.description = tagString(ds, 0x0008, 0x103e);
    r.patientName = tagString(ds, 0x0010, 0x0010);
    r.patientId = tagString(ds, 0x0010, 0x0020);
    r.studyDate = tagString(ds, 0x0008, 0x0020);
    r.frameOfReferenceUid = tagString(ds, 0x0020, 0x0052);
    r.studyTime = tagString(ds, 0x0008, 0x0030);
    r.studyDescription = tagString(ds, 0x0008, 0x1030);
    r.bodyPart = tagString(ds, 0x0018, 0x0015);
    r.imageType = tagString(ds, 0x0008, 0x0008);
    r.seriesNumber = tagInt(ds, 0x0020, 0x0011).value_or(0);
    r.instanceNumber = tagInt(ds, 0x0020, 0x0013).value_or(0);
    r.sliceThickness = tagDoubles(ds, 0x0018, 0x0050).value_or(std::vector<double>{0.0})[0];
}

// Geometry and rescale of a frame: looked up in the per-frame item first, then
// in the shared item, then (classic objects) at the top level.
struct FrameGroups {
    const gdcm::DataSet* perFrame = nullptr;
    const gdcm::DataSet* shared = nullptr;
};

std::optional<std::vector<double>> frameValues(const FrameGroups& g, std::uint16_t seqGroup,
                                               std::uint16_t seqElement, std::uint16_t group,
                                               std::uint16_t element) {
    for (const gdcm::DataSet* ds : {g.perFrame, g.shared}) {
        if (ds == nullptr) {
            continue;
        }
        if (const SequenceItem item = firstItem(*ds, seqGroup, seqElement)) {
            if (auto v = tagDoubles(*item, group, element)) {
                return v;
            }
        }
    }
    return std::nullopt;
}

std::string frameType(const FrameGroups& g) {
    // MR, CT and the generic frame type sequences all carry FrameType (0008,9007).
    for (const gdcm::DataSet* ds : {g.perFrame, g.shared}) {
        if (ds == nullptr) {
            continue;
        }
        for (const std::uint16_t element : {0x9226, 0x9329, 0x9012}) {
            if (const SequenceItem item = firstItem(*ds, 0x0018, element)) {
                const std::string t = tagString(*item, 0x0008, 0x9007);
                if (!t.empty()) {
                    return t;
                }
            }
        }
    }
    return {};
}

bool allFinite(const std::vector<double>& values, std::size_t count) {
    return std::all_of(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(count),
                       [](double v) { return std::isfinite(v); });
}

// Sets the image's position, directions and pixel spacing from the elements that
// are there. Returns why they cannot be used (naming the element), else "": a
// direction that is no unit vector, or two that are not perpendicular, would make
// every later step (the normal, the stack, resampling) compute with NaN
// (fuzz_dicom: a zero column direction).
std::string applyGeometry(ImageRecord& r, const std::optional<std::vector<double>>& ipp,
                          const std::optional<std::vector<double>>& iop,
                          const std::optional<std::vector<double>>& spacing) {
    if (ipp && ipp->size() >= 3 && iop && iop->size() >= 6) {
        if (!allFinite(*ipp, 3)) {
            return "ImagePositionPatient (0020,0032) holds a value that is not a finite number";
        }
        if (!allFinite(*iop, 6)) {
            return "ImageOrientationPatient (0020,0037) holds a value that is not a finite number";
        }
        const glm::dvec3 row((*iop)[0], (*iop)[1], (*iop)[2]);
        const glm::dvec3 column((*iop)[3], (*iop)[4], (*iop)[5]);
        const double lr = glm::length(row);
        const double lc = glm::length(column);
        // Unit vectors, allowing for the few digits some writers keep.
        if (std::abs(lr - 1.0) > 0.01 || std::abs(lc - 1.0) > 0.01) {
            char lengths[64];
            std::snprintf(lengths, sizeof lengths, "%.4g and %.4g", lr, lc);
            return "ImageOrientationPatient (0020,0037): its row and column directions are no "
                   "unit vectors (lengths " +
                   std::string(lengths) + ")";
        }
        if (std::abs(glm::dot(row / lr, column / lc)) > 0.01) {
            return "ImageOrientationPatient (0020,0037): its row and column directions are not "
                   "perpendicular";
        }
        r.hasPosition = true;
        r.position = {(*ipp)[0], (*ipp)[1], (*ipp)[2]};
        r.rowDir = row / lr;
        r.colDir = column / lc;
    }
    if (spacing && spacing->size() >= 2 && allFinite(*spacing, 2) && (*spacing)[0] > 0.0 &&
        (*spacing)[1] > 0.0) {
        r.hasPixelSpacing = true;
        // PixelSpacing is [between rows, between columns].
        r.pixelSpacing = {(*spacing)[1], (*spacing)[0]};
    }
    return {};
}

// Projection radiographs (and some converted images) carry only the spacing at
// the detector, ImagerPixelSpacing (0018,1164): used, as other viewers do, with
// a warning, since at the patient it is smaller by the geometric magnification.
void useImagerPixelSpacing(const gdcm::DataSet& ds, ImageRecord& r) {
    const auto imager = tagDoubles(ds, 0x0018, 0x1164);
    if (!imager || imager->size() < 2 || !allFinite(*imager, 2) || (*imager)[0] <= 0.0 ||
        (*imager)[1] <= 0.0) {
        return;
    }
    r.hasPixelSpacing = true;
    r.pixelSpacing = {(*imager)[1], (*imager)[0]};
    r.warnings.push_back("no PixelSpacing (0028,0030): ImagerPixelSpacing (0018,1164) used, the "
                         "spacing at the detector (not corrected for magnification)");
}

FileScan skip(std::string reason) {
    return FileScan{{}, std::move(reason)};
}

// The transfer syntaxes Lucent decodes (GDCM, and dcmdjpls for JPEG-LS);
// nullptr for anything else, so the user hears about it at scan time.
const char* supportedSyntaxName(const std::string& uid) {
    static const std::pair<const char*, const char*> known[] = {
        {"1.2.840.10008.1.2", "Implicit VR Little Endian"},
        {"1.2.840.10008.1.2.1", "Explicit VR Little Endian"},
        {"1.2.840.10008.1.2.2", "Explicit VR Big Endian"},
        {"1.2.840.10008.1.2.1.99", "Deflated Explicit VR Little Endian"},
        {"1.2.840.10008.1.2.4.50", "JPEG Baseline"},
        {"1.2.840.10008.1.2.4.51", "JPEG Extended"},
        {"1.2.840.10008.1.2.4.57", "JPEG Lossless"},
        {"1.2.840.10008.1.2.4.70", "JPEG Lossless SV1"},
        {"1.2.840.10008.1.2.4.80", "JPEG-LS Lossless"},
        {"1.2.840.10008.1.2.4.81", "JPEG-LS Near-Lossless"},
        {"1.2.840.10008.1.2.4.90", "JPEG 2000 Lossless"},
        {"1.2.840.10008.1.2.4.91", "JPEG 2000"},
        {"1.2.840.10008.1.2.5", "RLE Lossless"},
    };
    for (const auto& [u, name] : known) {
        if (uid == u) {
            return name;
        }
    }
    return nullptr;
}

// Why an object holds no image to load (a segmentation, no Rows/Columns, no
// Pixel Data), else "".
std::string notAnImage(const gdcm::DataSet& ds, const ImageRecord& base,
                       const DicomStructure& structure) {
    if (base.sopClassUid == "1.2.840.10008.5.1.4.1.1.66.4") {
        return "DICOM Segmentation object: not an image series";
    }
    if (!ds.FindDataElement(gdcm::Tag(0x0028, 0x0010)) ||
        !ds.FindDataElement(gdcm::Tag(0x0028, 0x0011))) {
        return "no image (Rows/Columns missing): " + (base.modality.empty()
                                                          ? std::string("non-image object")
                                                          : base.modality + " object");
    }
    if (!structure.hasPixelData && structure.transferSyntax != kDeflated) {
        return "no pixel data (7FE0,0010 missing)";
    }
    return {};
}

// The bits of the pixels, checked; why they cannot be read, else "".
std::string readPixelLayout(const gdcm::DataSet& ds, const std::string& syntax, PixelLayout& px) {
    px.bitsAllocated = tagUShort(ds, 0x0028, 0x0100).value_or(16);
    px.bitsStored = tagUShort(ds, 0x0028, 0x0101).value_or(px.bitsAllocated);
    px.highBit = tagUShort(ds, 0x0028, 0x0102).value_or(px.bitsStored - 1);
    px.isSigned = tagUShort(ds, 0x0028, 0x0103).value_or(0) == 1;
    px.transferSyntax = syntax;
    if (px.bitsAllocated != 8 && px.bitsAllocated != 16 && px.bitsAllocated != 32) {
        return "unsupported BitsAllocated " + std::to_string(px.bitsAllocated);
    }
    if (px.bitsStored < 1 || px.bitsStored > px.bitsAllocated || px.highBit < px.bitsStored - 1 ||
        px.highBit >= px.bitsAllocated) {
        return "inconsistent BitsStored " + std::to_string(px.bitsStored) + " / HighBit " +
               std::to_string(px.highBit) + " for BitsAllocated " +
               std::to_string(px.bitsAllocated);
    }
    return {};
}

// Colour (three samples: RGB, YBR) and palette colour images are 2D stacks; what
// their samples are is checked here. Why they cannot be read, else "".
std::string readColourLayout(const gdcm::DataSet& ds, int samples, PixelLayout& px) {
    px.samplesPerPixel = samples;
    px.planarConfiguration = tagUShort(ds, 0x0028, 0x0006).value_or(0) == 1 ? 1 : 0;
    px.photometric = trimmed(tagString(ds, 0x0028, 0x0004));
    if (px.photometric.empty()) {
        px.photometric = samples == 3 ? "RGB" : "MONOCHROME2";
    }
    const std::string& pi = px.photometric;
    const std::string what = "PhotometricInterpretation (0028,0004) " + pi + " with " +
                             std::to_string(samples) + " sample(s) per pixel";
    if (samples == 1) {
        if (pi != "MONOCHROME1" && pi != "MONOCHROME2" && pi != "PALETTE COLOR") {
            return "unsupported " + what;
        }
        return {};
    }
    if (samples != 3) {
        return "unsupported SamplesPerPixel (0028,0002) " + std::to_string(samples) +
               " (ARGB and CMYK are retired)";
    }
    if (pi != "RGB" && pi != "YBR_FULL" && pi != "YBR_FULL_422" && pi != "YBR_RCT" &&
        pi != "YBR_ICT") {
        return "unsupported " + what;
    }
    if (px.bitsAllocated != 8) {
        return "unsupported colour image with BitsAllocated " + std::to_string(px.bitsAllocated) +
               " (8 is read)";
    }
    return {};
}

// The bytes of one uncompressed frame: YBR_FULL_422 keeps two luminance samples
// and one pair of chrominance samples for every two pixels (PS3.3 C.7.6.3.1.2).
std::uint64_t storedFrameBytes(const PixelLayout& px) {
    const std::uint64_t pixels = static_cast<std::uint64_t>(px.rows) * px.columns;
    const std::uint64_t bytes = static_cast<std::uint64_t>(px.bitsAllocated / 8);
    if (px.photometric == "YBR_FULL_422") {
        return pixels * 2 * bytes;
    }
    return pixels * bytes * static_cast<std::uint64_t>(px.samplesPerPixel);
}

// Uncompressed pixel data: whole in the file, and where little endian frames
// start (`offset`, read straight from the file; 0 when GDCM decodes them).
std::string nativePixels(const DicomStructure& structure, std::uint64_t expected,
                         std::uint64_t& offset) {
    if (!structure.hasPixelData || structure.encapsulated) {
        return {};
    }
    if (std::string truncated = truncatedPixelData(structure); !truncated.empty()) {
        return truncated;
    }
    if (structure.pixelLength < expected) { // within the file, as checked above
        return "truncated pixel data: expected " + std::to_string(expected) + " bytes, found " +
               std::to_string(structure.pixelLength);
    }
    if (structure.transferSyntax == kExplicitLE || structure.transferSyntax == kImplicitLE) {
        offset = structure.pixelOffset;
    }
    return {};
}

// One record a frame of an Enhanced CT/MR, from its per-frame and shared groups.
FileScan enhancedFrames(const ImageRecord& base, const gdcm::SequenceOfItems& perFrame,
                        const SequenceItem& shared, int frames, std::uint64_t offset,
                        std::uint64_t frameBytes) {
    FileScan out;
    for (int f = 0; f < frames; ++f) {
        ImageRecord r = base;
        r.enhanced = true;
        r.frame = f;
        const FrameGroups g{&perFrame.GetItem(f + 1).GetNestedDataSet(), shared.dataSet};
        const std::string unusable =
            applyGeometry(r, frameValues(g, 0x0020, 0x9113, 0x0020, 0x0032),
                          frameValues(g, 0x0020, 0x9116, 0x0020, 0x0037),
                          frameValues(g, 0x0028, 0x9110, 0x0028, 0x0030));
        if (!unusable.empty()) {
            return skip("frame " + std::to_string(f + 1) + ": " + unusable);
        }
        if (auto t = frameValues(g, 0x0028, 0x9110, 0x0018, 0x0050)) {
            r.sliceThickness = (*t)[0];
        }
        if (auto s = frameValues(g, 0x0028, 0x9145, 0x0028, 0x1053)) {
            r.slope = (*s)[0];
        }
        if (auto i = frameValues(g, 0x0028, 0x9145, 0x0028, 0x1052)) {
            r.intercept = (*i)[0];
        }
        const std::string ft = frameType(g);
        if (!ft.empty()) {
            r.imageType = ft;
            r.localizer = hasWord(ft, "LOCALIZER");
        }
        r.pixelOffset = offset == 0 ? 0 : offset + frameBytes * f;
        out.images.push_back(std::move(r));
    }
    return out;
}

} // namespace

FileScan scanDicomFile(const std::string& file) {
    try {
        const DicomStructure structure = checkDicomStructure(file);
        if (!structure.ok) {
            return skip(structure.problem == "not a DICOM file" || structure.problem == "empty file"
                            ? "not a DICOM file (" + structure.problem + ")"
                            : "corrupt DICOM file: " + structure.problem);
        }
        quietGdcm();
        DataSetStream stream(file, structure);
        gdcm::Reader reader;
        reader.SetStream(stream);
        if (!reader.ReadUpToTag(kPixelData, {kPixelData})) {
            return skip("not a DICOM file (or its header is unreadable)");
        }
        const gdcm::File& gfile = reader.GetFile();
        const gdcm::DataSet& ds = gfile.GetDataSet();
        const std::string& syntax = structure.transferSyntax;
        if (supportedSyntaxName(syntax) == nullptr) {
            return skip("unsupported transfer syntax " + syntax);
        }

        gdcm::MediaStorage ms;
        ms.SetFromFile(gfile);
        if (ms == gdcm::MediaStorage::MediaStorageDirectoryStorage) {
            return skip("DICOMDIR: open it directly to load the files it lists");
        }

        ImageRecord base;
        base.file = file;
        base.warnings = structure.warnings;
        readCommon(ds, base);
        if (const std::string why = notAnImage(ds, base, structure); !why.empty()) {
            return skip(why);
        }

        const int rows = tagUShort(ds, 0x0028, 0x0010).value_or(0);
        const int cols = tagUShort(ds, 0x0028, 0x0011).value_or(0);
        if (rows <= 0 || cols <= 0) {
            return skip("zero-size image (Rows " + std::to_string(rows) + ", Columns " +
                        std::to_string(cols) + ")");
        }
        base.samplesPerPixel = tagUShort(ds, 0x0028, 0x0002).value_or(1);
        PixelLayout& px = base.pixels;
        px.rows = rows;
        px.columns = cols;
        if (const std::string wrong = readPixelLayout(ds, syntax, px); !wrong.empty()) {
            return skip(wrong);
        }
        if (const std::string wrong = readColourLayout(ds, base.samplesPerPixel, px);
            !wrong.empty()) {
            return skip(wrong);
        }

        const int frames = std::max(1, tagInt(ds, 0x0028, 0x0008).value_or(1));
        base.frameCount = frames;
        const std::uint64_t frameBytes = storedFrameBytes(px);
        std::uint64_t offset = 0;
        if (const std::string wrong =
                nativePixels(structure, frameBytes * std::uint64_t(frames), offset);
            !wrong.empty()) {
            return skip(wrong);
        }

        base.localizer = hasWord(base.imageType, "LOCALIZER");
        const auto slope = tagDoubles(ds, 0x0028, 0x1053);
        const auto intercept = tagDoubles(ds, 0x0028, 0x1052);
        base.slope = slope ? (*slope)[0] : 1.0;
        base.intercept = intercept ? (*intercept)[0] : 0.0;

        const SequenceItem shared = firstItem(ds, 0x5200, 0x9229);
        const gdcm::SmartPointer<gdcm::SequenceOfItems> perFrame =
            ds.FindDataElement(kPerFrameGroups) ? ds.GetDataElement(kPerFrameGroups).GetValueAsSQ()
                                                : nullptr;
        if (perFrame && perFrame->GetNumberOfItems() >= static_cast<std::size_t>(frames)) {
            return enhancedFrames(base, *perFrame, shared, frames, offset, frameBytes);
        }

        FileScan out;
        const std::string unusable =
            applyGeometry(base, tagDoubles(ds, 0x0020, 0x0032), tagDoubles(ds, 0x0020, 0x0037),
                          tagDoubles(ds, 0x0028, 0x0030));
        if (!base.hasPixelSpacing) {
            useImagerPixelSpacing(ds, base);
        }
        if (!unusable.empty()) {
            return skip(unusable);
        }
        if (frames == 1) {
            base.pixelOffset = offset;
            out.images.push_back(std::move(base));
            return out;
        }
        // Legacy multi-frame: frames stacked along the normal at SpacingBetweenSlices;
        // without them (ultrasound, XA cine) the frames are a 2D stack in time.
        const auto between = tagDoubles(ds, 0x0018, 0x0088);
        const bool cine = !base.hasPosition || !between || (*between)[0] <= 0.0;
        const glm::dvec3 normal = glm::normalize(glm::cross(base.rowDir, base.colDir));
        for (int f = 0; f < frames; ++f) {
            ImageRecord r = base;
            r.frame = f;
            r.cine = cine;
            r.position = cine ? base.position : base.position + normal * ((*between)[0] * f);
            r.pixelOffset = offset == 0 ? 0 : offset + frameBytes * f;
            out.images.push_back(std::move(r));
        }
        return out;
    } catch (const std::exception& e) {
        return skip(std::string("unreadable header: ") + e.what());
    }
}

bool isDicomdir(const std::string& file) {
    if (fs::path(file).filename() == "DICOMDIR") {
        return true;
    }
    const DicomStructure structure = checkDicomStructure(file);
    if (!structure.ok) {
        return false;
    }
    quietGdcm();
    DataSetStream stream(file, structure);
    gdcm::Reader reader;
    reader.SetStream(stream);
    if (!reader.ReadUpToTag(gdcm::Tag(0x0004, 0x1220))) {
        return false;
    }
    gdcm::MediaStorage ms;
    ms.SetFromFile(reader.GetFile());
    return ms == gdcm::MediaStorage::MediaStorageDirectoryStorage;
}

std::vector<std::string> dicomdirReferences(const std::string& dicomdir) {
    const DicomStructure structure = checkDicomStructure(dicomdir);
    if (!structure.ok) {
        throw LoadError(dicomdir + ": not a readable DICOMDIR (" + structure.problem + ")");
    }
    quietGdcm();
    DataSetStream stream(dicomdir, structure);
    gdcm::Reader reader;
    reader.SetStream(stream);
    if (!reader.Read()) {
        throw LoadError(dicomdir + ": not a readable DICOMDIR");
    }
    const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
    const gdcm::Tag records(0x0004, 0x1220);
    if (!ds.FindDataElement(records)) {
        throw LoadError(dicomdir + ": DICOMDIR without a Directory Record Sequence (0004,1220)");
    }
    const auto seq = ds.GetDataElement(records).GetValueAsSQ();
    const fs::path root = fs::path(dicomdir).parent_path();
    std::vector<std::string> files;
    for (std::size_t i = 1; seq && i <= seq->GetNumberOfItems(); ++i) {
        const gdcm::DataSet& item = seq->GetItem(i).GetNestedDataSet();
        const std::string id = tagString(item, 0x0004, 0x1500);
        if (id.empty()) {
            continue;
        }
        fs::path p = root;
        std::size_t start = 0;
        // ReferencedFileID: path components separated by backslashes.
        while (start <= id.size()) {
            const std::size_t end = id.find('\\', start);
            p /= id.substr(start, end == std::string::npos ? std::string::npos : end - start);
            if (end == std::string::npos) {
                break;
            }
            start = end + 1;
        }
        files.push_back(p.string());
    }
    return files;
}

} // namespace lucent
