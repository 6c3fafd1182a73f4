#pragma once
// The instances of a series that measurements refer to: what an SR needs of them
// (SOP class and instance, each image's plane) and the plane tests between a
// measurement and an acquired slice. DCMTK stays private.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/measure/Measurement.h"

namespace lucent {

// One instance of the series: a single-frame image with its plane, or a multi-frame
// object (frames > 1, its planes per frame not read: measurements on it go as 3D).
struct ReferencedImage {
    std::filesystem::path file;
    std::string sopClassUid;
    std::string sopInstanceUid;
    glm::dvec3 position{0.0};         // ImagePositionPatient: centre of the first pixel
    glm::dvec3 rowDir{1.0, 0.0, 0.0}; // direction of increasing column
    glm::dvec3 colDir{0.0, 1.0, 0.0}; // direction of increasing row
    glm::dvec2 spacing{1.0};          // x: between columns, y: between rows (mm)
    int rows = 0;
    int columns = 0;
    int frames = 1;

    glm::dvec3 normal() const { return glm::normalize(glm::cross(rowDir, colDir)); }
    // DICOM's image coordinates (column, row), (0,0) the top-left corner of the
    // top-left pixel, of the projection of p onto the image plane.
    glm::dvec2 imageCoordinates(const glm::dvec3& p) const;
    // The patient point of image coordinates on the image plane.
    glm::dvec3 patientPoint(const glm::dvec2& columnRow) const;
    // The image as a SlicePlane: u along the rows, v down the columns, pixel centres
    // at whole numbers (the pixel size is the column spacing).
    SlicePlane plane() const;
};

struct ReferencedSeries {
    std::string studyUid;
    std::string seriesUid;
    std::string frameOfReferenceUid;
    std::string modality;
    std::vector<ReferencedImage> images;

    // The image whose plane holds every point: parallel to `plane` (normals within
    // 1e-4 rad) and no point further than toleranceMm from the image plane. None
    // for an oblique plane or points between slices.
    const ReferencedImage* acquiredImageOf(const Measurement& m, double toleranceMm = 0.01) const;
    const ReferencedImage* find(const std::string& sopInstanceUid) const;
};

class ReportError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Reads the headers (never the pixels) of a series' files. Files of other series
// than the first file's are passed over. Throws ReportError naming the file when
// one is not DICOM, or is a single-frame image without its plane.
ReferencedSeries readReferencedSeries(const std::vector<std::filesystem::path>& files);

} // namespace lucent
