#include "core/report/ReferencedSeries.h"

#include <cmath>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include "core/report/DicomItemValues.h"

namespace lucent {

namespace fs = std::filesystem;

glm::dvec2 ReferencedImage::imageCoordinates(const glm::dvec3& p) const {
    const glm::dvec3 d = p - position;
    return {glm::dot(d, rowDir) / spacing.x + 0.5, glm::dot(d, colDir) / spacing.y + 0.5};
}

glm::dvec3 ReferencedImage::patientPoint(const glm::dvec2& c) const {
    return position + (c.x - 0.5) * spacing.x * rowDir + (c.y - 0.5) * spacing.y * colDir;
}

SlicePlane ReferencedImage::plane() const {
    SlicePlane s;
    s.u = rowDir;
    s.v = colDir;
    s.pixelSize = spacing.x;
    s.width = columns;
    s.height = rows;
    s.centre = patientPoint({0.5 * columns, 0.5 * rows});
    return s;
}

const ReferencedImage* ReferencedSeries::acquiredImageOf(const Measurement& m,
                                                         double toleranceMm) const {
    if (m.points.empty()) {
        return nullptr;
    }
    const glm::dvec3 normal = m.plane.normal();
    for (const ReferencedImage& image : images) {
        if (image.frames != 1) {
            continue;
        }
        const glm::dvec3 n = image.normal();
        if (glm::length(glm::cross(n, normal)) > 1e-4) {
            continue; // not parallel: an oblique plane (a thin axis-aligned one may still fit)
        }
        bool onImage = true;
        for (const glm::dvec3& p : m.points) {
            onImage = onImage && std::abs(glm::dot(p - image.position, n)) <= toleranceMm;
        }
        if (onImage) {
            return &image;
        }
    }
    return nullptr;
}

const ReferencedImage* ReferencedSeries::find(const std::string& sopInstanceUid) const {
    for (const ReferencedImage& image : images) {
        if (image.sopInstanceUid == sopInstanceUid) {
            return &image;
        }
    }
    return nullptr;
}

using dicomitem::numbers;
using dicomitem::text;

ReferencedSeries readReferencedSeries(const std::vector<fs::path>& files) {
    ReferencedSeries series;
    for (const fs::path& file : files) {
        DcmFileFormat format;
        if (format.loadFile(file.c_str(), EXS_Unknown, EGL_noChange, 4096, ERM_autoDetect).bad()) {
            throw ReportError(file.string() + ": not a DICOM file");
        }
        DcmDataset& d = *format.getDataset();
        const std::string seriesUid = text(d, DCM_SeriesInstanceUID);
        if (series.seriesUid.empty()) {
            series.seriesUid = seriesUid;
            series.studyUid = text(d, DCM_StudyInstanceUID);
            series.frameOfReferenceUid = text(d, DCM_FrameOfReferenceUID);
            series.modality = text(d, DCM_Modality);
        } else if (seriesUid != series.seriesUid) {
            continue;
        }
        ReferencedImage image;
        image.file = file;
        image.sopClassUid = text(d, DCM_SOPClassUID);
        image.sopInstanceUid = text(d, DCM_SOPInstanceUID);
        Sint32 frames = 1;
        if (d.findAndGetSint32(DCM_NumberOfFrames, frames).good() && frames > 1) {
            if (image.sopInstanceUid.empty()) {
                throw ReportError(file.string() + ": lacks its SOP Instance UID");
            }
            image.frames = frames;
            series.images.push_back(std::move(image));
            continue;
        }
        double orientation[6] = {};
        double spacing[2] = {};
        Uint16 rows = 0, columns = 0;
        if (image.sopInstanceUid.empty() ||
            !numbers(d, DCM_ImagePositionPatient, &image.position.x, 3) ||
            !numbers(d, DCM_ImageOrientationPatient, orientation, 6) ||
            !numbers(d, DCM_PixelSpacing, spacing, 2) || d.findAndGetUint16(DCM_Rows, rows).bad() ||
            d.findAndGetUint16(DCM_Columns, columns).bad()) {
            throw ReportError(file.string() +
                              ": lacks the SOP Instance UID, image position, orientation, pixel "
                              "spacing or size that a measurement's image reference needs");
        }
        image.rowDir = glm::normalize(glm::dvec3(orientation[0], orientation[1], orientation[2]));
        image.colDir = glm::normalize(glm::dvec3(orientation[3], orientation[4], orientation[5]));
        image.spacing = {spacing[1], spacing[0]}; // PixelSpacing is row spacing \ column spacing
        image.rows = rows;
        image.columns = columns;
        series.images.push_back(std::move(image));
    }
    return series;
}

} // namespace lucent
