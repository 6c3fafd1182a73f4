// Reading a DICOM SEG with dcmdata: the Segment Sequence, each frame's segment, source image
// and plane from the functional groups (per frame, else shared), the frames' bits straight
// into the segments' masks. Written by any program (dcmqi, highdicom, dcmjs, Lucent).
#include <algorithm>
#include <cmath>
#include <optional>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmiod/cielabutil.h>

#include "core/segdicom/SegmentationDicom.h"
#include "core/segdicom/SegmentationDicomItems_p.h"
#include "core/segdicom/SliceImages_p.h"

namespace lucent {

namespace fs = std::filesystem;
using namespace segdicom;

namespace {

// What one frame's functional groups say.
struct FrameFacts {
    int segmentNumber = -1;
    std::vector<std::string> sources; // SOP Instance UIDs of its source images
    std::optional<glm::dvec3> position;
    std::optional<std::pair<glm::dvec3, glm::dvec3>> orientation;
};

FrameFacts frameFacts(DcmItem* perFrame, DcmItem* shared) {
    FrameFacts f;
    // Per-frame first, then shared: a group is in one of them.
    for (DcmItem* groups : {perFrame, shared}) {
        if (groups == nullptr) {
            continue;
        }
        if (DcmItem* id = item(*groups, DCM_SegmentIdentificationSequence);
            id != nullptr && f.segmentNumber < 0) {
            Uint16 n = 0;
            if (id->findAndGetUint16(DCM_ReferencedSegmentNumber, n).good()) {
                f.segmentNumber = n;
            }
        }
        if (DcmItem* p = item(*groups, DCM_PlanePositionSequence); p != nullptr && !f.position) {
            double v[3];
            if (numbers(*p, DCM_ImagePositionPatient, v, 3)) {
                f.position = glm::dvec3(v[0], v[1], v[2]);
            }
        }
        if (DcmItem* o = item(*groups, DCM_PlaneOrientationSequence);
            o != nullptr && !f.orientation) {
            double v[6];
            if (numbers(*o, DCM_ImageOrientationPatient, v, 6)) {
                f.orientation = {glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5])};
            }
        }
        if (f.sources.empty()) {
            for (DcmItem* derivation : items(*groups, DCM_DerivationImageSequence)) {
                for (DcmItem* source : items(*derivation, DCM_SourceImageSequence)) {
                    const std::string uid = text(*source, DCM_ReferencedSOPInstanceUID);
                    if (!uid.empty()) {
                        f.sources.push_back(uid);
                    }
                }
            }
        }
    }
    return f;
}

std::array<std::uint8_t, 3> colourOf(DcmItem& segment, const CodedConcept& type) {
    Uint16 lab[3];
    bool ok = true;
    for (unsigned long i = 0; i < 3; ++i) {
        ok = ok && segment.findAndGetUint16(DCM_RecommendedDisplayCIELabValue, lab[i], i).good();
    }
    if (!ok) { // no colour stored: the table's for its type, else grey
        for (const SegmentKind& k : segmentKinds()) {
            if (k.type.value == type.value && k.type.scheme == type.scheme) {
                return {static_cast<std::uint8_t>(k.colour >> 16),
                        static_cast<std::uint8_t>(k.colour >> 8),
                        static_cast<std::uint8_t>(k.colour)};
            }
        }
        return {128, 128, 128};
    }
    double r = 0.0, g = 0.0, b = 0.0;
    IODCIELabUtil::dicomLab2RGB(r, g, b, lab[0], lab[1], lab[2]);
    const auto byte = [](double v) {
        return static_cast<std::uint8_t>(std::clamp(std::lround(v * 255.0), 0L, 255L));
    };
    return {byte(r), byte(g), byte(b)};
}

// The Segment Sequence: each segment's description, by its number.
std::vector<std::pair<Uint16, Segment>> segmentsOf(DcmDataset& d, const fs::path& file,
                                                   const VolumeGeometry& grid) {
    std::vector<std::pair<Uint16, Segment>> out;
    for (DcmItem* s : items(d, DCM_SegmentSequence)) {
        Uint16 number = 0;
        if (s->findAndGetUint16(DCM_SegmentNumber, number).bad() || number == 0) {
            throw SegmentationDicomError(file.string() + ": a segment without Segment Number");
        }
        Segment segment;
        segment.name = text(*s, DCM_SegmentLabel);
        if (segment.name.empty()) {
            segment.name = "Segment " + std::to_string(number);
        }
        segment.category = codeOf(*s, DCM_SegmentedPropertyCategoryCodeSequence);
        segment.type = codeOf(*s, DCM_SegmentedPropertyTypeCodeSequence);
        segment.colour = colourOf(*s, segment.type);
        segment.algorithmType = text(*s, DCM_SegmentAlgorithmType);
        if (segment.algorithmType.empty()) {
            segment.algorithmType = "MANUAL";
        }
        segment.algorithmName = text(*s, DCM_SegmentAlgorithmName);
        segment.mask = std::make_shared<const SegmentMask>(grid.dims);
        out.emplace_back(number, std::move(segment));
    }
    if (out.empty()) {
        throw SegmentationDicomError(file.string() + ": no Segment Sequence");
    }
    std::sort(out.begin(), out.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    return out;
}

// The slice of `series` a frame lies on: by its source image, else by its plane position.
int sliceOf(const FrameFacts& f, std::size_t frame, const ReferencedSeries& series,
            const VolumeGeometry& grid, const SegmentationDicomHeader& h, const fs::path& file) {
    const std::string where = file.string() + ": frame " + std::to_string(frame + 1);
    if (f.orientation && !sameOrientation(grid, f.orientation->first, f.orientation->second)) {
        throw SegmentationDicomError(where + " is not oriented as the slices of series " +
                                     series.seriesUid +
                                     " (another orientation: Lucent cannot show it on them)");
    }
    for (const std::string& uid : f.sources) {
        if (const ReferencedImage* image = series.find(uid); image != nullptr) {
            if (!sameOrientation(grid, image->rowDir, image->colDir)) {
                throw SegmentationDicomError(where + " lies on image " + uid +
                                             ", which is not oriented as the series' volume");
            }
            const int k = sliceAt(grid, image->position);
            if (k >= 0) {
                return k;
            }
        }
    }
    if (!f.sources.empty() && std::none_of(f.sources.begin(), f.sources.end(),
                                           [&](const std::string& u) { return series.find(u); })) {
        throw SegmentationDicomError(where + " was derived from image " + f.sources.front() +
                                     ", which is not in series " + series.seriesUid);
    }
    if (!h.frameOfReferenceUid.empty() && !series.frameOfReferenceUid.empty() &&
        h.frameOfReferenceUid != series.frameOfReferenceUid) {
        throw SegmentationDicomError(file.string() + ": its Frame of Reference " +
                                     h.frameOfReferenceUid + " is not that of series " +
                                     series.seriesUid);
    }
    if (!f.position) {
        throw SegmentationDicomError(where + " has neither a source image nor a plane position");
    }
    if (!f.orientation) {
        throw SegmentationDicomError(where + " has no plane orientation");
    }
    const int k = sliceAt(grid, *f.position);
    if (k < 0) {
        const glm::dvec3& p = *f.position;
        throw SegmentationDicomError(where + " at (" + std::to_string(p.x) + ", " +
                                     std::to_string(p.y) + ", " + std::to_string(p.z) +
                                     ") lies on no slice of series " + series.seriesUid);
    }
    return k;
}

} // namespace

SegmentationDicomHeader readSegmentationDicomHeader(const fs::path& file) {
    DcmFileFormat format;
    loadSegmentation(format, file, false);
    return headerOf(*format.getDataset(), file);
}

bool isSegmentationDicom(const fs::path& file) {
    DcmFileFormat format;
    return format.loadFile(file.c_str(), EXS_Unknown, EGL_noChange, 64, ERM_autoDetect).good() &&
           text(*format.getDataset(), DCM_SOPClassUID) == kSegmentationSopClassUid;
}

ReadSegmentationDicom readSegmentationDicom(const fs::path& file, const ReferencedSeries& series,
                                            const VolumeGeometry& grid) {
    DcmFileFormat format;
    loadSegmentation(format, file, true);
    DcmDataset& d = *format.getDataset();
    ReadSegmentationDicom out;
    out.header = headerOf(d, file);
    const PixelFrames pixels = pixelFramesOf(d, file);
    if (pixels.rows != grid.dims.y || pixels.columns != grid.dims.x) {
        throw SegmentationDicomError(
            file.string() + ": frames of " + std::to_string(pixels.columns) + "x" +
            std::to_string(pixels.rows) + " pixels, the slices of series " + series.seriesUid +
            " have " + std::to_string(grid.dims.x) + "x" + std::to_string(grid.dims.y));
    }
    out.fractional = pixels.fractional;
    out.readOnly = pixels.fractional;
    out.frames = pixels.frames;
    if (pixels.binaryAsFractional) {
        out.notes.push_back("FRACTIONAL frames that hold only 0 and 1 (binary masks as dcmjs "
                            "writes them): read as binary");
    }
    auto numbered = segmentsOf(d, file, grid);
    std::vector<SegmentMask> masks;
    for (std::size_t s = 0; s < numbered.size(); ++s) {
        masks.emplace_back(grid.dims);
    }
    const auto perFrame = items(d, DCM_PerFrameFunctionalGroupsSequence);
    DcmItem* shared = item(d, DCM_SharedFunctionalGroupsSequence);
    if (perFrame.size() < pixels.frames) {
        throw SegmentationDicomError(file.string() + ": " + std::to_string(pixels.frames) +
                                     " frames but " + std::to_string(perFrame.size()) +
                                     " per-frame functional groups");
    }
    for (std::size_t n = 0; n < pixels.frames; ++n) {
        const FrameFacts f = frameFacts(perFrame[n], shared);
        const auto it = std::find_if(numbered.begin(), numbered.end(),
                                     [&](const auto& s) { return s.first == f.segmentNumber; });
        if (it == numbered.end()) {
            throw SegmentationDicomError(file.string() + ": frame " + std::to_string(n + 1) +
                                         " names segment " + std::to_string(f.segmentNumber) +
                                         ", which the Segment Sequence does not describe");
        }
        const int k = sliceOf(f, n, series, grid, out.header, file);
        pixels.addFrame(n, masks[static_cast<std::size_t>(it - numbered.begin())], k);
    }
    for (std::size_t s = 0; s < numbered.size(); ++s) {
        numbered[s].second.mask = std::make_shared<const SegmentMask>(std::move(masks[s]));
        out.segmentNumbers.push_back(numbered[s].first);
        out.segments.push_back(std::move(numbered[s].second));
    }
    return out;
}

std::vector<std::uint32_t> addSegments(Segmentation& segmentation,
                                       const std::vector<Segment>& segments) {
    std::vector<std::uint32_t> ids;
    for (const Segment& s : segments) {
        const std::uint32_t id = segmentation.add(s.name);
        SegmentKind kind{s.name, s.category, s.type, 0};
        segmentation.setKind(id, kind);
        segmentation.setColour(id, s.colour);
        const bool manual = s.algorithmType == "MANUAL" || s.algorithmType.empty();
        const std::string algorithm =
            manual ? std::string() : (s.algorithmName.empty() ? s.algorithmType : s.algorithmName);
        segmentation.setMask(id, *s.mask, "Open " + s.name, algorithm,
                             s.algorithmType == "AUTOMATIC");
        ids.push_back(id);
    }
    return ids;
}

} // namespace lucent
