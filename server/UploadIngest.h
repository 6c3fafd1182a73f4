#pragma once
// Instances uploaded to lucent-server (POST /studies, STOW-RS style): one
// DICOM Part 10 file (Content-Type application/dicom) or several
// (multipart/related; type="application/dicom"), checked whole before any
// enters the study store, so that a refused upload leaves nothing behind.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "server/UploadParts.h"

namespace lucent::remote {

struct UploadSummary {
    int stored = 0;
    int alreadyStored = 0;
    std::vector<std::string> series; // series instance UIDs, each once
};

// Checks every part (a DICOM Part 10 file with study, series and SOP instance
// UIDs), then adds them to the store at storeRoot. Throws UploadError naming
// the part and what is wrong (nothing stored then), or StoreError.
UploadSummary storeUpload(const std::filesystem::path& storeRoot, std::string_view contentType,
                          std::string_view body);

} // namespace lucent::remote
