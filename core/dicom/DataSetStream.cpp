#include "core/dicom/DataSetStream_p.h"

#include <algorithm>

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

DataSetStream::DataSetStream(const std::string& file, const DicomStructure& structure)
    : std::istream(nullptr), file_(file) {
    const std::size_t end =
        std::min<std::size_t>(file_.size(), static_cast<std::size_t>(structure.dataSetEnd));
    bytes_.view(file_.data(), file_.data() != nullptr ? end : 0);
    rdbuf(&bytes_);
    if (file_.data() == nullptr) {
        setstate(std::ios_base::failbit);
    }
}

} // namespace lucent
