#include "core/pet/SuvDicom.h"

#include <charconv>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include <gdcmReader.h>
#include <gdcmSequenceOfItems.h>

namespace lucent {

namespace {

// An element's text without padding; "" when absent or empty.
std::string tagString(const gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element) {
    const gdcm::Tag tag(group, element);
    const gdcm::ByteValue* bv =
        ds.FindDataElement(tag) ? ds.GetDataElement(tag).GetByteValue() : nullptr;
    if (bv == nullptr || bv->GetPointer() == nullptr) {
        return {};
    }
    const std::string text(bv->GetPointer(), bv->GetLength());
    const std::string padding(" \0", 2); // DICOM pads with spaces (text) or a NUL (UI)
    const std::size_t first = text.find_first_not_of(padding);
    const std::size_t last = text.find_last_not_of(padding);
    return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

// The first value of a DS element; nullopt when absent or not a number.
std::optional<double> firstDouble(const gdcm::DataSet& ds, std::uint16_t group,
                                  std::uint16_t element) {
    std::string text = tagString(ds, group, element);
    text = text.substr(0, text.find('\\'));
    if (!text.empty() && text.front() == '+') {
        text.erase(0, 1);
    }
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size()) {
        return std::nullopt;
    }
    return v;
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

// The first item of RadiopharmaceuticalInformationSequence (0054,0016). The sequence is held
// while its item is read: GDCM may build it anew from raw bytes (implicit VR).
void readRadiopharmaceutical(const gdcm::DataSet& ds, SuvParameters& p) {
    const gdcm::Tag tag(0x0054, 0x0016);
    if (!ds.FindDataElement(tag)) {
        return;
    }
    const gdcm::SmartPointer<gdcm::SequenceOfItems> sequence =
        ds.GetDataElement(tag).GetValueAsSQ();
    if (!sequence || sequence->GetNumberOfItems() == 0) {
        return;
    }
    const gdcm::DataSet& item = sequence->GetItem(1).GetNestedDataSet();
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
