#pragma once
// A structural check of a DICOM file before any library parses it: walks the
// element stream (tags and lengths only, sequences and encapsulated fragments
// included) up to the Pixel Data element. GDCM as packaged aborts on some
// truncated or malformed headers, so nothing reaches it unchecked.

#include <cstdint>
#include <string>
#include <vector>

namespace lucent {

struct DicomStructure {
    bool ok = false;                // the element stream is sound up to Pixel Data
    std::string problem;            // why not, in words (with the byte offset)
    std::string transferSyntax;     // the data set's: the meta header's unless the data set differs
    bool metaSyntaxWrong = false;   // the meta header names another transfer syntax
    std::uint64_t metaSyntaxAt = 0; // the (0002,0010) element, where it is
    std::uint64_t metaGroupLengthAt = 0; // the value of (0002,0000), where it is (0: none)
    bool metaGroupLengthPast = false;    // (0002,0000) says the group ends past its last element
    bool metaGroupLengthWrong = false;   // (0002,0000) says another end than its last element's
    std::uint64_t metaEnd = 0;           // where the meta group's last element ends
    bool hasPixelData = false;
    bool encapsulated = false;     // compressed fragments
    std::uint64_t pixelOffset = 0; // first byte of the Pixel Data value
    std::uint64_t pixelLength = 0; // its length (defined lengths only)
    std::uint64_t fileSize = 0;
    // The file's size, or where zero padding after the data set starts.
    std::uint64_t dataSetEnd = 0;
    // What was untidy but read as DCMTK or GDCM read it: zero padding after the
    // data set, a wrong meta group length, a data set in implicit VR under a meta
    // header that says explicit. In words, with the byte offset or count.
    std::vector<std::string> warnings;
};

DicomStructure checkDicomStructure(const std::string& file);

// Why uncompressed Pixel Data runs past the end of the file, else "": the walk
// lets it through for the scan to say so, but GDCM allocates the declared length
// before it reads, so no whole read may see such a file.
std::string truncatedPixelData(const DicomStructure& structure);

} // namespace lucent
