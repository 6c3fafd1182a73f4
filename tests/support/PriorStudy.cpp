#include "tests/support/PriorStudy.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>

#include "tests/support/DicomCopy.h"

namespace lucent::test {

namespace {

void shiftPosition(DcmDataset& ds, const glm::dvec3& shift, const std::filesystem::path& file) {
    glm::dvec3 p;
    for (int n = 0; n < 3; ++n) {
        Float64 v = 0.0;
        if (ds.findAndGetFloat64(DCM_ImagePositionPatient, v, static_cast<unsigned long>(n))
                .bad()) {
            throw std::runtime_error(file.string() + ": no ImagePositionPatient");
        }
        p[n] = v + shift[n];
    }
    char text[128];
    std::snprintf(text, sizeof text, "%.4f\\%.4f\\%.4f", p.x, p.y, p.z);
    putElement(ds, DCM_ImagePositionPatient, text, file);
}

} // namespace

PriorStudy writePriorStudy(const std::filesystem::path& source, const std::filesystem::path& target,
                           const std::string& studyDate, const glm::dvec3& shift) {
    PriorStudy prior;
    prior.studyUid = newUid(SITE_STUDY_UID_ROOT);
    prior.seriesUid = newUid(SITE_SERIES_UID_ROOT);
    const bool moved = shift != glm::dvec3(0.0);
    prior.frameOfReferenceUid = moved ? newUid(SITE_INSTANCE_UID_ROOT) : std::string();
    std::filesystem::create_directories(target);
    for (const std::filesystem::path& file : filesIn(source)) {
        DcmFileFormat dicom;
        if (dicom.loadFile(file.c_str()).bad()) {
            continue; // not DICOM
        }
        DcmDataset& ds = *dicom.getDataset();
        putElement(ds, DCM_StudyInstanceUID, prior.studyUid, file);
        putElement(ds, DCM_SeriesInstanceUID, prior.seriesUid, file);
        const std::string sop = newUid(SITE_INSTANCE_UID_ROOT);
        putElement(ds, DCM_SOPInstanceUID, sop, file);
        putElement(ds, DCM_StudyDate, studyDate, file);
        if (moved) {
            putElement(ds, DCM_FrameOfReferenceUID, prior.frameOfReferenceUid, file);
            shiftPosition(ds, shift, file);
        } else if (OFString frame; ds.findAndGetOFString(DCM_FrameOfReferenceUID, frame).good()) {
            prior.frameOfReferenceUid = frame.c_str();
        }
        const std::filesystem::path out = target / (sop + ".dcm");
        // The meta header follows the new SOP Instance UID.
        if (dicom
                .saveFile(out.c_str(), EXS_Unknown, EET_UndefinedLength, EGL_recalcGL, EPD_noChange,
                          0, 0, EWM_updateMeta)
                .bad()) {
            throw std::runtime_error(out.string() + ": cannot write the prior's copy of " +
                                     file.string());
        }
        prior.files.push_back(out);
    }
    if (prior.files.empty()) {
        throw std::runtime_error(source.string() + ": no DICOM file to copy");
    }
    return prior;
}

} // namespace lucent::test
