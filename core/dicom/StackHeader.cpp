// The stack's extra header elements, read with GDCM up to the pixel data through
// the checked stream (DataSetStream_p.h), as the scan reads headers.
#include "core/dicom/StackHeader_p.h"

#include <algorithm>
#include <cstring>

#include <gdcmReader.h>

#include "core/dicom/DataSetStream_p.h"
#include "core/dicom/DicomStructure.h"
#include "core/dicom/DicomTags_p.h"
#include "core/io/LoadControl.h"

namespace lucent {
namespace {

const gdcm::ByteValue* valueOf(const gdcm::DataSet& ds, std::uint16_t group,
                               std::uint16_t element) {
    const gdcm::Tag tag(group, element);
    if (!ds.FindDataElement(tag)) {
        return nullptr;
    }
    const gdcm::ByteValue* bv = ds.GetDataElement(tag).GetByteValue();
    return bv != nullptr && bv->GetPointer() != nullptr ? bv : nullptr;
}

std::vector<std::uint16_t> words(const gdcm::ByteValue& bv) {
    std::vector<std::uint16_t> out(bv.GetLength() / 2);
    std::memcpy(out.data(), bv.GetPointer(), out.size() * 2);
    return out;
}

// One channel's table. Its descriptor: entries (0 means 65536), first stored
// value mapped, bits per entry (8 or 16). Its data: one 16-bit word an entry, or
// (8-bit entries from some writers) one byte an entry.
std::vector<std::uint8_t> readChannel(const std::string& file, const gdcm::DataSet& ds, int c,
                                      int& firstMapped) {
    static const char* const names[] = {"Red", "Green", "Blue"};
    const auto element = static_cast<std::uint16_t>(0x1101 + c);
    const std::string where = file + ": " + names[c] + "PaletteColorLookupTable";
    const gdcm::ByteValue* descriptor = valueOf(ds, 0x0028, element);
    if (descriptor == nullptr || descriptor->GetLength() < 6) {
        throw LoadError(where + "Descriptor (0028," + std::to_string(1101 + c) +
                        ") is missing or short");
    }
    const std::vector<std::uint16_t> d = words(*descriptor);
    const std::size_t count = d[0] == 0 ? 65536 : d[0];
    const int bits = d[2];
    firstMapped = d[1];
    const gdcm::ByteValue* data = valueOf(ds, 0x0028, static_cast<std::uint16_t>(0x1201 + c));
    if (data == nullptr) {
        const bool segmented = valueOf(ds, 0x0028, static_cast<std::uint16_t>(0x1221 + c));
        throw LoadError(where + (segmented ? "Data is segmented (0028,122x), which Lucent "
                                             "does not read"
                                           : "Data (0028,120x) is missing"));
    }
    if (bits != 8 && bits != 16) {
        throw LoadError(where + "Descriptor: " + std::to_string(bits) +
                        " bits per entry (8 or 16 expected)");
    }
    std::vector<std::uint8_t> table(count);
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(data->GetPointer());
    if (bits == 8 && data->GetLength() == count) {
        std::copy_n(bytes, count, table.begin());
        return table;
    }
    if (data->GetLength() < 2 * count) {
        throw LoadError(where + "Data holds " + std::to_string(data->GetLength()) + " bytes for " +
                        std::to_string(count) + " entries");
    }
    const std::vector<std::uint16_t> w = words(*data);
    // 16-bit entries keep their high byte; 8-bit entries in words their low one,
    // unless the writer scaled them to 16 bits after all.
    const bool wide =
        bits == 16 || std::any_of(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(count),
                                  [](std::uint16_t v) { return v > 255; });
    for (std::size_t i = 0; i < count; ++i) {
        table[i] = static_cast<std::uint8_t>(wide ? w[i] >> 8 : w[i]);
    }
    return table;
}

} // namespace

const std::uint8_t* PaletteTable::colourOf(std::int64_t stored, std::uint8_t rgb[3]) const {
    const auto last = static_cast<std::int64_t>(entries[0].size()) - 1;
    const auto i =
        static_cast<std::size_t>(std::clamp<std::int64_t>(stored - firstMapped, 0, last));
    for (int c = 0; c < 3; ++c) {
        rgb[c] = entries[static_cast<std::size_t>(c)]
                        [std::min(i, entries[static_cast<std::size_t>(c)].size() - 1)];
    }
    return rgb;
}

StackHeader readStackHeader(const std::string& file, bool palette) {
    const DicomStructure structure = checkDicomStructure(file);
    if (!structure.ok) {
        throw LoadError(file + ": corrupt DICOM file: " + structure.problem);
    }
    DataSetStream stream(file, structure);
    gdcm::Reader reader;
    reader.SetStream(stream);
    const gdcm::Tag pixelData(0x7fe0, 0x0010);
    if (!reader.ReadUpToTag(pixelData, {pixelData})) {
        throw LoadError(file + ": header unreadable");
    }
    const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
    StackHeader h;
    const auto centre = tagDoubles(ds, 0x0028, 0x1050);
    const auto width = tagDoubles(ds, 0x0028, 0x1051);
    if (centre && width && (*width)[0] > 0.0) {
        h.window = {(*centre)[0], (*width)[0]};
    }
    if (const auto t = tagDoubles(ds, 0x0018, 0x1063); t && (*t)[0] > 0.0) {
        h.frameTimeMs = (*t)[0];
    }
    if (const auto v = tagDoubles(ds, 0x0018, 0x1065)) {
        h.frameTimeVector = *v;
    }
    if (palette) {
        int first[3] = {0, 0, 0};
        for (int c = 0; c < 3; ++c) {
            h.palette.entries[static_cast<std::size_t>(c)] = readChannel(file, ds, c, first[c]);
        }
        h.palette.firstMapped = first[0];
    }
    return h;
}

} // namespace lucent
