#include "tests/support/PetFromCt.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcitem.h>
#include <dcmtk/dcmdata/dcuid.h>

#include "tests/support/DicomCopy.h"

namespace lucent::test {

namespace {

std::string tm(double secondsOfDay) {
    const int s = static_cast<int>(secondsOfDay);
    char text[32];
    std::snprintf(text, sizeof text, "%02d%02d%02d", s / 3600, s / 60 % 60, s % 60);
    return text;
}

std::string ds(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", v);
    return text;
}

void putRadiopharmaceutical(DcmDataset& ds, const PetHeader& h, const std::filesystem::path& f) {
    delete ds.remove(DCM_RadiopharmaceuticalInformationSequence);
    DcmItem* item = nullptr;
    if (ds.findOrCreateSequenceItem(DCM_RadiopharmaceuticalInformationSequence, item).bad()) {
        throw std::runtime_error(f.string() + ": cannot add the radiopharmaceutical item");
    }
    putElement(*item, DCM_Radiopharmaceutical, "Fluorodeoxyglucose", f);
    putElement(*item, DCM_RadionuclideTotalDose, h.totalDose, f);
    putElement(*item, DCM_RadionuclideHalfLife, h.halfLife, f);
    putElement(*item, DCM_RadiopharmaceuticalStartTime, h.startTime, f);
    putElement(*item, DCM_RadiopharmaceuticalStartDateTime, h.startDateTime, f);
}

void putPet(DcmDataset& d, const PetHeader& h, int n, const std::filesystem::path& f) {
    putElement(d, DCM_Modality, "PT", f);
    putElement(d, DCM_SOPClassUID, UID_PositronEmissionTomographyImageStorage, f);
    putElement(d, DCM_Units, h.units, f);
    putElement(d, DCM_CorrectedImage, h.correctedImage, f);
    putElement(d, DCM_DecayCorrection, h.decayCorrection, f);
    putElement(d, DCM_PatientWeight, h.patientWeight, f);
    putElement(d, DCM_SeriesDate, h.seriesDate, f);
    putElement(d, DCM_SeriesTime, h.seriesTime, f);
    putElement(d, DCM_AcquisitionDate, h.acquisitionDate, f);
    putElement(d, DCM_AcquisitionTime, tm(h.acquisitionStart + n * h.acquisitionStep), f);
    delete d.remove(DCM_AcquisitionDateTime);
    putElement(d, DCM_RescaleSlope, ds(h.slope + n * h.slopeStep), f);
    putElement(d, DCM_RescaleIntercept, "0", f);
    putRadiopharmaceutical(d, h, f);
}

} // namespace

PetSeries writePetFromCt(const std::filesystem::path& ctFolder, const std::filesystem::path& target,
                         const PetHeader& header) {
    PetSeries pet;
    pet.seriesUid = newUid(SITE_SERIES_UID_ROOT);
    std::filesystem::create_directories(target);
    for (const std::filesystem::path& file : filesIn(ctFolder)) {
        DcmFileFormat dicom;
        if (dicom.loadFile(file.c_str()).bad()) {
            continue; // not DICOM
        }
        DcmDataset& ds = *dicom.getDataset();
        const int n = static_cast<int>(pet.files.size());
        putPet(ds, header, n, file);
        putElement(ds, DCM_SeriesInstanceUID, pet.seriesUid, file);
        const std::string sop = newUid(SITE_INSTANCE_UID_ROOT);
        putElement(ds, DCM_SOPInstanceUID, sop, file);
        const std::filesystem::path out = target / (sop + ".dcm");
        if (dicom
                .saveFile(out.c_str(), EXS_Unknown, EET_UndefinedLength, EGL_recalcGL, EPD_noChange,
                          0, 0, EWM_updateMeta)
                .bad()) {
            throw std::runtime_error(out.string() + ": cannot write the PET copy of " +
                                     file.string());
        }
        pet.files.push_back(out);
        pet.slopes.push_back(header.slope + n * header.slopeStep);
    }
    if (pet.files.empty()) {
        throw std::runtime_error(ctFolder.string() + ": no DICOM file to copy");
    }
    return pet;
}

double storedActivity(const PetSeries& pet, const std::filesystem::path& file, int i, int j) {
    const auto n = std::find(pet.files.begin(), pet.files.end(), file) - pet.files.begin();
    DcmFileFormat dicom;
    const Uint16* pixels = nullptr;
    Uint16 columns = 0;
    if (n >= static_cast<long>(pet.files.size()) || dicom.loadFile(file.c_str()).bad() ||
        dicom.getDataset()->findAndGetUint16(DCM_Columns, columns).bad() ||
        dicom.getDataset()->findAndGetUint16Array(DCM_PixelData, pixels).bad()) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    const int stored =
        pixels[static_cast<std::size_t>(j) * columns + static_cast<std::size_t>(i)] & 0x0fff;
    return stored * pet.slopes[static_cast<std::size_t>(n)];
}

} // namespace lucent::test
