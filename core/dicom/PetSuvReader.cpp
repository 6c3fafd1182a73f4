#include "core/dicom/PetSuvReader.h"

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gdcmReader.h>

#include "core/dicom/DicomTags_p.h"

namespace lucent {

namespace {

// The first value of a DS element; nullopt when absent or not a number.
std::optional<double> firstDouble(const gdcm::DataSet& ds, std::uint16_t group,
                                  std::uint16_t element) {
    const std::optional<std::vector<double>> values = tagDoubles(ds, group, element);
    return values && !values->empty() ? std::optional<double>(values->front()) : std::nullopt;
}

gdcm::File readHeader(const std::filesystem::path& file) {
    gdcm::Reader reader;
    reader.SetFileName(file.string().c_str());
    if (!reader.ReadUpToTag(gdcm::Tag(0x7fe0, 0x0010))) {
        throw std::runtime_error(file.string() + ": not a readable DICOM file");
    }
    return reader.GetFile();
}

std::optional<double> acquisitionTime(const gdcm::DataSet& ds) {
    return dicomDateTimeSeconds(tagString(ds, 0x0008, 0x0022), tagString(ds, 0x0008, 0x0032));
}

// The first item of RadiopharmaceuticalInformationSequence (0054,0016).
void readRadiopharmaceutical(const gdcm::DataSet& ds, SuvParameters& p) {
    const SequenceItem radiopharmaceutical = firstItem(ds, 0x0054, 0x0016);
    if (!radiopharmaceutical) {
        return;
    }
    const gdcm::DataSet& item = *radiopharmaceutical;
    p.totalDoseBq = firstDouble(item, 0x0018, 0x1074);
    p.halfLifeS = firstDouble(item, 0x0018, 0x1075);
    p.injectionTime = dicomDtSeconds(tagString(item, 0x0018, 0x1078));
    if (!p.injectionTime) {
        p.injectionTime =
            dicomDateTimeSeconds(tagString(ds, 0x0008, 0x0021), tagString(item, 0x0018, 0x1072));
    }
}

} // namespace

SuvParameters readSuvParameters(const std::filesystem::path& dicomFile) {
    const gdcm::File file = readHeader(dicomFile);
    const gdcm::DataSet& ds = file.GetDataSet();
    SuvParameters p;
    p.units = tagString(ds, 0x0054, 0x1001);
    p.correctedImage = tagString(ds, 0x0028, 0x0051);
    p.decayCorrection = tagString(ds, 0x0054, 0x1102);
    p.patientWeightKg = firstDouble(ds, 0x0010, 0x1030);
    readRadiopharmaceutical(ds, p);
    p.seriesTime =
        dicomDateTimeSeconds(tagString(ds, 0x0008, 0x0021), tagString(ds, 0x0008, 0x0031));
    p.earliestAcquisitionTime = acquisitionTime(ds);
    return p;
}

SuvParameters readSuvParameters(std::span<const std::filesystem::path> seriesFiles) {
    if (seriesFiles.empty()) {
        throw std::runtime_error("readSuvParameters: the series has no file");
    }
    SuvParameters p = readSuvParameters(seriesFiles.front());
    for (const std::filesystem::path& path : seriesFiles.subspan(1)) {
        const gdcm::File file = readHeader(path);
        const auto t = acquisitionTime(file.GetDataSet());
        if (t && (!p.earliestAcquisitionTime || *t < *p.earliestAcquisitionTime)) {
            p.earliestAcquisitionTime = t;
        }
    }
    return p;
}

} // namespace lucent
