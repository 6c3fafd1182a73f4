#pragma once
// DICOM instances as files: what a file is (its SOP class and instance, its
// transfer syntax, its study and series), and the instances under a path.
// DCMTK stays private.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace lucent {

class InstanceFileError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// What senders and exporters need of a file: from its meta header and data set.
struct InstanceHeader {
    std::filesystem::path file;
    std::string sopClassUid;
    std::string sopInstanceUid;
    std::string transferSyntaxUid;
    std::string studyUid;
    std::string seriesUid;
};

// Reads the header of a DICOM file (not its pixels). Throws InstanceFileError
// naming the file when it is not DICOM or lacks a SOP class, SOP instance or
// transfer syntax UID.
InstanceHeader readInstanceHeader(const std::filesystem::path& file);

// The instances under `path` (a file, or a folder searched recursively) in
// file name order, only those of the series `seriesUid` when it is not empty.
// Files that are not DICOM instances (DICOMDIRs among them) are passed over:
// each is named in `passedOver` with the reason. Throws InstanceFileError
// when `path` does not exist.
std::vector<InstanceHeader> collectInstances(const std::filesystem::path& path,
                                             const std::string& seriesUid,
                                             std::vector<std::string>& passedOver);

} // namespace lucent
