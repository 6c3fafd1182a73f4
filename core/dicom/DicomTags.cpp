#include "core/dicom/DicomTags_p.h"

#include <charconv>
#include <cstring>

#include <gdcmSequenceOfItems.h>

namespace lucent {

std::string trimmed(std::string_view s) {
    const auto isPad = [](char c) {
        return c == ' ' || c == '\0' || c == '\t' || c == '\r' || c == '\n';
    };
    while (!s.empty() && isPad(s.front())) {
        s.remove_prefix(1);
    }
    while (!s.empty() && isPad(s.back())) {
        s.remove_suffix(1);
    }
    return std::string(s);
}

bool hasWord(std::string_view multiValue, std::string_view word) {
    std::size_t start = 0;
    while (start <= multiValue.size()) {
        const std::size_t end = multiValue.find('\\', start);
        const std::string_view part = multiValue.substr(
            start, end == std::string_view::npos ? std::string_view::npos : end - start);
        if (trimmed(part) == word) {
            return true;
        }
        if (end == std::string_view::npos) {
            break;
        }
        start = end + 1;
    }
    return false;
}

namespace {

const gdcm::ByteValue* byteValue(const gdcm::DataSet& ds, std::uint16_t group,
                                 std::uint16_t element) {
    const gdcm::Tag tag(group, element);
    if (!ds.FindDataElement(tag)) {
        return nullptr;
    }
    return ds.GetDataElement(tag).GetByteValue();
}

} // namespace

std::string tagString(const gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element) {
    const gdcm::ByteValue* bv = byteValue(ds, group, element);
    if (bv == nullptr || bv->GetPointer() == nullptr) {
        return {};
    }
    return trimmed(std::string_view(bv->GetPointer(), bv->GetLength()));
}

std::optional<std::vector<double>> tagDoubles(const gdcm::DataSet& ds, std::uint16_t group,
                                              std::uint16_t element) {
    const std::string text = tagString(ds, group, element);
    if (text.empty()) {
        return std::nullopt;
    }
    std::vector<double> values;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = text.find('\\', start);
        std::string part = trimmed(std::string_view(text).substr(
            start, end == std::string::npos ? std::string::npos : end - start));
        if (!part.empty() && part.front() == '+') {
            part.erase(0, 1);
        }
        double v = 0.0;
        const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
        if (ec != std::errc() || ptr != part.data() + part.size()) {
            return std::nullopt;
        }
        values.push_back(v);
        if (end == std::string::npos) {
            break;
        }
        start = end + 1;
    }
    return values;
}

std::optional<int> tagInt(const gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element) {
    const auto v = tagDoubles(ds, group, element);
    if (!v) {
        return std::nullopt;
    }
    return static_cast<int>((*v)[0]);
}

std::optional<int> tagUShort(const gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element) {
    const gdcm::ByteValue* bv = byteValue(ds, group, element);
    if (bv == nullptr || bv->GetLength() < 2 || bv->GetPointer() == nullptr) {
        return std::nullopt;
    }
    std::uint16_t v = 0;
    std::memcpy(&v, bv->GetPointer(), sizeof v);
    return v;
}

SequenceItem firstItem(const gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element) {
    const gdcm::Tag tag(group, element);
    if (!ds.FindDataElement(tag)) {
        return {};
    }
    SequenceItem item{ds.GetDataElement(tag).GetValueAsSQ(), nullptr};
    if (item.sequence && item.sequence->GetNumberOfItems() > 0) {
        item.dataSet = &item.sequence->GetItem(1).GetNestedDataSet();
    }
    return item;
}

} // namespace lucent
