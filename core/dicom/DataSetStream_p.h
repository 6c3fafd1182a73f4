#pragma once
// The bytes of a DICOM file up to the end of its data set, as the std::istream
// that GDCM reads: zero padding after the data set, which the structural walk
// accepts as DCMTK does, never reaches GDCM, whose reader aborts on some
// lengths of it (7 zero bytes after Pixel Data; fuzz_dicom). A file whose meta
// header says another encoding than its data set's, or a wrong group length,
// gets the meta header the walk read: GDCM's own guesses over such files
// allocated gigabytes (fuzz_dicom). Private to core/dicom.

#include <istream>
#include <string>
#include <vector>

#include "core/dicom/DicomStructure.h"
#include "core/dicom/MappedFile_p.h"

namespace lucent {

class DataSetStream : public std::istream {
public:
    // `structure` is checkDicomStructure(file)'s, which must be ok.
    DataSetStream(const std::string& file, const DicomStructure& structure);

private:
    // The bytes of a file with its meta header as the walk read it: (0002,0010)
    // naming Implicit VR Little Endian where the data set is so under a meta that
    // says explicit, and (0002,0000) counting the group's elements.
    static std::vector<unsigned char> correctedMeta(const unsigned char* data, std::size_t end,
                                                    const DicomStructure& structure);

    // A get area over the mapped bytes, with seeking (GDCM seeks back and forth).
    class Bytes : public std::streambuf {
    public:
        void view(const unsigned char* data, std::size_t size);

    protected:
        pos_type seekoff(off_type off, std::ios_base::seekdir dir,
                         std::ios_base::openmode which) override;
        pos_type seekpos(pos_type pos, std::ios_base::openmode which) override;
    };

    MappedFile file_;
    std::vector<unsigned char> patched_; // the bytes with the meta header corrected
    Bytes bytes_;
};

} // namespace lucent
