#pragma once

#include <glm/glm.hpp>

#include <string>

#include "core/io/SeriesEntry.h"

namespace lucent {

// The plane of a series' images: the patient axis nearest the image normal when it
// is within kObliqueDegrees of it, else oblique (a gantry tilt of 18.5 degrees is
// still axial; a plane halfway between two axes is oblique).
enum class SliceOrientation { Axial, Coronal, Sagittal, Oblique };
inline constexpr double kObliqueDegrees = 30.0;

// rowDir, colDir: the image's row and column directions (LPS unit vectors).
SliceOrientation sliceOrientationOf(const glm::dvec3& rowDir, const glm::dvec3& colDir);
const char* sliceOrientationName(SliceOrientation orientation); // "axial", ...

// One series as the hanging-protocol matcher sees it.
struct HangingSeries {
    std::string seriesUid, studyUid, patientId;
    std::string studyDate, studyTime, studyDescription; // DICOM DA and TM text
    std::string modality, bodyPart, description;
    int seriesNumber = 0;
    double sliceThickness = 0; // mm; 0 when unknown
    SliceOrientation orientation = SliceOrientation::Axial;
    int instances = 0; // images (slices or frames) of the entry
    SeriesKind kind = SeriesKind::Volume;
    int studyOrder = 0; // 0 current, 1 prior 1, ...; -1 not related (see orderStudies)
    std::string path;   // what to open it from: the scanned path (folder or file)
    std::string id;     // its catalog id (SeriesEntry::id)
};

// The facts of a catalog entry; path: where the catalog was scanned from. studyOrder
// is left 0 (orderStudies sets it).
HangingSeries hangingSeriesOf(const SeriesEntry& entry, const std::string& path);

} // namespace lucent
