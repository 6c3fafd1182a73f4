#pragma once
// Copies of DICOM instances for leaving the workstation: to a folder or a ZIP
// file, optionally de-identified (PS3.15 Basic Profile, core/dicom/Deidentifier:
// one UID map for the whole export, so references between the exported
// instances still hold; pixels untouched), optionally with a DICOMDIR.
//
// Layout, the same in a folder and a ZIP: DICOM/STnnnn/SEnnnn/IMnnnnnn, the
// components of DICOM file IDs (at most 8 upper-case characters), so a
// DICOMDIR can reference every file.
//
// The export is built in a temporary sibling of the output and renamed into
// place when whole: a failure or a cancel leaves nothing at the output path.
// The sources are only read.

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <vector>

#include "core/exchange/InstanceFiles.h"

namespace lucent {

class ExportError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct ExportOptions {
    bool anonymize = false;
    bool dicomdir = false;
    std::function<void(int done, int total)> onProgress; // after each file
    std::stop_token stop;                                // cancel: ExportError, nothing written
};

struct ExportResult {
    std::filesystem::path output;
    int files = 0; // instances exported
    bool zip = false;
    std::vector<std::string> fileIds; // each instance's path in the export, in the order given
};

// Exports `instances` to `output`: a ZIP file when its name ends in ".zip",
// else a folder. Throws ExportError naming the output or the file at fault
// when the output exists already, lies inside a source folder, or a file
// cannot be read, de-identified or written.
ExportResult exportInstances(const std::vector<InstanceHeader>& instances,
                             const std::filesystem::path& output, const ExportOptions& options);

} // namespace lucent
