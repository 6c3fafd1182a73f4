#include "ReferenceDicom.h"

#include <cmath>
#include <stdexcept>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcobject.h>
#include <dcmtk/oflog/oflog.h>

namespace lucent::test {

ReferenceImage readReferenceImage(const std::string& file, bool detectEncoding) {
    // DCMTK's warnings on untidy files (the quirks corpus) are no test output.
    static const bool quiet = [] {
        OFLog::configure(OFLogger::ERROR_LOG_LEVEL);
        return true;
    }();
    (void)quiet;
    DcmFileFormat ff;
    const OFBool detecting = dcmAutoDetectDatasetXfer.get();
    dcmAutoDetectDatasetXfer.set(detectEncoding);
    const bool read = ff.loadFile(file.c_str()).good();
    dcmAutoDetectDatasetXfer.set(detecting);
    if (!read) {
        throw std::runtime_error("DCMTK cannot read " + file);
    }
    DcmDataset& d = *ff.getDataset();
    ReferenceImage r;
    r.file = file;
    Float64 v[6] = {};
    for (int n = 0; n < 3; ++n) {
        d.findAndGetFloat64(DCM_ImagePositionPatient, v[n], n);
    }
    r.position = {v[0], v[1], v[2]};
    for (int n = 0; n < 6; ++n) {
        d.findAndGetFloat64(DCM_ImageOrientationPatient, v[n], n);
    }
    r.rowDir = {v[0], v[1], v[2]};
    r.colDir = {v[3], v[4], v[5]};
    const DcmTagKey spacing =
        d.tagExists(DCM_PixelSpacing) ? DCM_PixelSpacing : DCM_ImagerPixelSpacing;
    d.findAndGetFloat64(spacing, v[0], 0);
    d.findAndGetFloat64(spacing, v[1], 1);
    r.spacing = {v[1], v[0]};
    Uint16 rows = 0, cols = 0, stored = 16, repr = 0;
    d.findAndGetUint16(DCM_Rows, rows);
    d.findAndGetUint16(DCM_Columns, cols);
    d.findAndGetUint16(DCM_BitsStored, stored);
    d.findAndGetUint16(DCM_PixelRepresentation, repr);
    r.rows = rows;
    r.columns = cols;
    Float64 slope = 1.0, intercept = 0.0;
    // DCMTK sets the value to 0 when the element is missing (an MR has no rescale).
    if (d.findAndGetFloat64(DCM_RescaleSlope, slope).bad()) {
        slope = 1.0;
    }
    if (d.findAndGetFloat64(DCM_RescaleIntercept, intercept).bad()) {
        intercept = 0.0;
    }
    const Uint16* px = nullptr;
    if (d.findAndGetUint16Array(DCM_PixelData, px).bad() || px == nullptr) {
        throw std::runtime_error("DCMTK finds no 16-bit pixel data in " + file);
    }
    r.values.resize(std::size_t(rows) * cols);
    const long mask = (1L << stored) - 1;
    for (std::size_t n = 0; n < r.values.size(); ++n) {
        long raw = px[n] & mask;
        if (repr == 1 && (raw & (1L << (stored - 1)))) {
            raw -= 1L << stored;
        }
        r.values[n] = static_cast<double>(raw) * slope + intercept;
    }
    return r;
}

bool ReferenceImage::sample(const glm::dvec3& lps, double& value, double& distanceFromPlane) const {
    const glm::dvec3 d = lps - position;
    distanceFromPlane = std::abs(glm::dot(d, glm::normalize(glm::cross(rowDir, colDir))));
    const double a = glm::dot(d, rowDir) / spacing.x;
    const double b = glm::dot(d, colDir) / spacing.y;
    if (a < 0.0 || b < 0.0 || a > columns - 1 || b > rows - 1) {
        return false;
    }
    const int a0 = std::min(static_cast<int>(a), columns - 2);
    const int b0 = std::min(static_cast<int>(b), rows - 2);
    const double fa = a - a0, fb = b - b0;
    value = (1 - fb) * ((1 - fa) * at(a0, b0) + fa * at(a0 + 1, b0)) +
            fb * ((1 - fa) * at(a0, b0 + 1) + fa * at(a0 + 1, b0 + 1));
    return true;
}

} // namespace lucent::test
