#include "core/dicom/DataSetStream_p.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace lucent {

void DataSetStream::Bytes::view(const unsigned char* data, std::size_t size) {
    char* begin = reinterpret_cast<char*>(const_cast<unsigned char*>(data));
    setg(begin, begin, begin + size);
}

DataSetStream::Bytes::pos_type DataSetStream::Bytes::seekoff(off_type off,
                                                             std::ios_base::seekdir dir,
                                                             std::ios_base::openmode which) {
    if (!(which & std::ios_base::in)) {
        return pos_type(off_type(-1));
    }
    const off_type size = egptr() - eback();
    const off_type base = dir == std::ios_base::beg   ? 0
                          : dir == std::ios_base::cur ? gptr() - eback()
                                                      : size;
    const off_type to = base + off;
    if (to < 0 || to > size) {
        return pos_type(off_type(-1));
    }
    setg(eback(), eback() + to, egptr());
    return pos_type(to);
}

DataSetStream::Bytes::pos_type DataSetStream::Bytes::seekpos(pos_type pos,
                                                             std::ios_base::openmode which) {
    return seekoff(off_type(pos), std::ios_base::beg, which);
}

std::vector<unsigned char> DataSetStream::correctedMeta(const unsigned char* data, std::size_t end,
                                                        const DicomStructure& structure) {
    static constexpr unsigned char kImplicit[] = "1.2.840.10008.1.2"; // 17 + its NUL pad
    std::vector<unsigned char> out(data, data + end);
    std::size_t metaEnd = structure.metaEnd;
    if (structure.metaSyntaxWrong) {
        const std::size_t at = structure.metaSyntaxAt;
        const std::size_t oldLength = data[at + 6] | data[at + 7] << 8;
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(at + 8),
                  out.begin() + static_cast<std::ptrdiff_t>(at + 8 + oldLength));
        out.insert(out.begin() + static_cast<std::ptrdiff_t>(at + 8), kImplicit,
                   kImplicit + sizeof kImplicit);
        out[at + 6] = sizeof kImplicit;
        out[at + 7] = 0;
        metaEnd = metaEnd - oldLength + sizeof kImplicit;
    }
    if (const std::size_t g = structure.metaGroupLengthAt; g != 0) {
        // The group's length as walked: GDCM starts the data set where it says.
        const auto length = static_cast<std::uint32_t>(metaEnd - (g + 4));
        std::memcpy(out.data() + g, &length, 4); // little endian, as x86 and the meta
    }
    return out;
}

DataSetStream::DataSetStream(const std::string& file, const DicomStructure& structure)
    : std::istream(nullptr), file_(file) {
    const std::size_t end =
        std::min<std::size_t>(file_.size(), static_cast<std::size_t>(structure.dataSetEnd));
    if (file_.data() != nullptr && (structure.metaSyntaxWrong || structure.metaGroupLengthWrong)) {
        patched_ = correctedMeta(file_.data(), end, structure);
        bytes_.view(patched_.data(), patched_.size());
    } else {
        bytes_.view(file_.data(), file_.data() != nullptr ? end : 0);
    }
    rdbuf(&bytes_);
    if (file_.data() == nullptr) {
        setstate(std::ios_base::failbit);
    }
}

} // namespace lucent
