#pragma once
// The segmentation of a series kept in the local study store as a DICOM SEG
// (core/segdicom/SegmentationDicom.h): one SEG per segmented series, in its own series of
// the same study, as the measurements' SR is (core/report/MeasurementArchive). The UI saves
// on every change of the Segmentation (revision(), ui/segmentation/SegmentationAutosave) and
// loads when it opens the series; the SEGs other programs stored with the study load too.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/report/ReferencedSeries.h"
#include "core/segdicom/SegmentationDicom.h"
#include "core/store/StudyStore.h"

namespace lucent {

class SegmentationArchive {
public:
    explicit SegmentationArchive(StudyStore& store, std::string softwareVersion = "Lucent");

    // Saves the segments of a stored series as a new SEG that replaces Lucent's previous SEG
    // of that series in one step (the index never names a half-written file); with no
    // segment left, removes that SEG. Returns the new SEG's SOP Instance UID, or "" when
    // removed. Throws SegmentationDicomError, ReportError or StoreError naming the series or
    // file; what was stored before stays then.
    std::string save(const std::string& seriesUid, const Segmentation& segmentation);

    struct Stored {
        std::filesystem::path file;
        SegmentationDicomHeader header;
    };
    // The SEGs of the series' study that refer to it (headers only).
    std::vector<Stored> find(const std::string& seriesUid);

    struct Loaded {
        std::filesystem::path file;
        ReadSegmentationDicom segmentation;
    };
    struct LoadResult {
        std::vector<Loaded> loaded;      // Lucent's first, then the others
        std::vector<std::string> errors; // SEGs that refer to the series but cannot be read
    };
    // Every SEG of the study that refers to the series, read onto `grid` (the volume the
    // series was loaded into).
    LoadResult load(const std::string& seriesUid, const VolumeGeometry& grid);

    // The series' images, headers read once.
    const ReferencedSeries& referencedSeries(const std::string& seriesUid);

private:
    StudyStore& store_;
    std::string softwareVersion_;
    std::map<std::string, ReferencedSeries> series_;
};

} // namespace lucent
