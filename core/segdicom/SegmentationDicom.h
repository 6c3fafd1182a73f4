#pragma once
// Segments as a DICOM Segmentation (SEG) object, written with DCMTK's dcmseg and read with
// dcmdata, both private to lucent_segdicom.
//
// Written: BINARY, one frame per segment and slice that holds a voxel (empty frames left out,
// an empty segment still described in the Segment Sequence), segment numbers 1..n in the list's
// order, each segment's label, SNOMED CT category and type, algorithm type (and name unless
// MANUAL) and its colour as the recommended CIELab display value. Per frame: Segment
// Identification, Derivation Image with the Source Image (the slice it lies on), Plane
// Position; Plane Orientation and Pixel Measures shared; the frames indexed by
// (ReferencedSegmentNumber, ImagePositionPatient). Patient and study from the source series,
// a new series (or the one given). Manufacturer "Lucent".
//
// Read: BINARY or FRACTIONAL (a voxel is set from half the maximum fractional value on, or from
// 1 when no voxel holds more, as dcmjs writes binary masks; such a SEG is read-only), overlapping
// segments, codes outside Lucent's table kept as stored. Each frame goes to the slice of the series
// it was derived from (its Source Image's SOP Instance UID), else to the slice at its Plane
// Position (within a tenth of a voxel), in the same Frame of Reference; its orientation must be the
// series'.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/report/ReferencedSeries.h"
#include "core/segmentation/Segmentation.h"

namespace lucent {

inline constexpr const char* kSegmentationSopClassUid = "1.2.840.10008.5.1.4.1.1.66.4";

// What is wrong with a SEG (or with writing one), naming the file.
class SegmentationDicomError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct SegmentationIdentity {
    std::string seriesUid;   // of the SEG's series; empty: a new one
    int seriesNumber = 9800; // where a study browser lists it
    std::string seriesDescription = "Lucent segmentation";
    std::string softwareVersion = "Lucent";
};

struct WrittenSegmentation {
    std::string sopInstanceUid;
    std::string seriesUid;
    std::string studyUid;
    std::size_t frames = 0;
};

// Writes the segments of `segmentation` (on the grid of the volume `source` was loaded into:
// each slice k must be one of its images) as a new SEG at `file`, whole or not at all. With
// fewer frames than segments (dcmseg 3.6.7 refuses that), each empty segment gets one empty
// frame on the first slice. Throws
// SegmentationDicomError naming the file (or the source image) and what is wrong.
WrittenSegmentation writeSegmentationDicom(const std::filesystem::path& file,
                                           const Segmentation& segmentation,
                                           const ReferencedSeries& source,
                                           const SegmentationIdentity& identity = {});

// What a SEG is and what it refers to, without its frames' pixels.
struct SegmentationDicomHeader {
    std::string sopInstanceUid;
    std::string seriesUid;
    std::string studyUid;
    std::string frameOfReferenceUid;
    std::string manufacturer;
    std::string seriesDescription;
    bool writtenByLucent = false;
    // The series its frames were derived from (Referenced Series Sequence and the frames'
    // Source Images; for the latter only the instances are named, see referencedInstances).
    std::vector<std::string> referencedSeries;
    std::vector<std::string> referencedInstances;
};

// Throws SegmentationDicomError naming the file when it is not DICOM or not a SEG.
SegmentationDicomHeader readSegmentationDicomHeader(const std::filesystem::path& file);
// True when the file is a DICOM SEG (its SOP class), without reading its content.
bool isSegmentationDicom(const std::filesystem::path& file);

struct ReadSegmentationDicom {
    SegmentationDicomHeader header;
    bool fractional = false;
    bool readOnly = false;          // what Lucent would not write back as it was (FRACTIONAL)
    std::vector<std::string> notes; // what Lucent read differently from the file's word
    // In Segment Number order; ids 0 (Segmentation gives them), masks on the series' grid.
    std::vector<Segment> segments;
    std::vector<std::uint16_t> segmentNumbers; // each segment's number in the SEG
    std::size_t frames = 0;
};

// Reads a SEG onto `grid`, the volume `series` was loaded into. Throws SegmentationDicomError
// naming the file and what is wrong: not DICOM, truncated, not a SEG, frames that refer to
// images of another series or lie off the grid, another orientation, another grid size.
ReadSegmentationDicom readSegmentationDicom(const std::filesystem::path& file,
                                            const ReferencedSeries& series,
                                            const VolumeGeometry& grid);

// Adds the segments read to `segmentation` (same grid) with their names, colours, codes,
// algorithm and voxels. Returns their ids.
std::vector<std::uint32_t> addSegments(Segmentation& segmentation,
                                       const std::vector<Segment>& segments);

} // namespace lucent
