#pragma once
// Typed access to GDCM data elements. Private to lucent_io (.cpp files only).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <gdcmDataSet.h>
#include <gdcmSequenceOfItems.h>

namespace lucent {

std::string trimmed(std::string_view s);
// True when a backslash-separated multi-value (e.g. ImageType) holds word.
bool hasWord(std::string_view multiValue, std::string_view word);

std::string tagString(const gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element);
// A DS or IS value (backslash-separated); nullopt when absent, empty or not numbers.
std::optional<std::vector<double>> tagDoubles(const gdcm::DataSet& ds, std::uint16_t group,
                                              std::uint16_t element);
std::optional<int> tagInt(const gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element);
// A US value (binary, host order as GDCM stores it).
std::optional<int> tagUShort(const gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element);
// The first item of a sequence. Holds the sequence: GDCM may build it anew
// from raw bytes (implicit VR), so a bare pointer into it could dangle.
struct SequenceItem {
    gdcm::SmartPointer<gdcm::SequenceOfItems> sequence;
    const gdcm::DataSet* dataSet = nullptr;
    explicit operator bool() const { return dataSet != nullptr; }
    const gdcm::DataSet& operator*() const { return *dataSet; }
};
SequenceItem firstItem(const gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element);

} // namespace lucent
