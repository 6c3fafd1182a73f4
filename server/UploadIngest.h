#pragma once
// Instances uploaded to lucent-server (POST /studies, STOW-RS style): one
// DICOM Part 10 file (Content-Type application/dicom) or several
// (multipart/related; type="application/dicom"), checked whole before any
// enters the study store, so that a refused upload leaves nothing behind.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace lucent::remote {

// Why an upload was refused, with the HTTP status that says so (400, 415).
class UploadError : public std::runtime_error {
public:
    UploadError(int status, const std::string& message)
        : std::runtime_error(message), status_(status) {}
    int status() const { return status_; }

private:
    int status_;
};

struct UploadSummary {
    int stored = 0;
    int alreadyStored = 0;
    std::vector<std::string> series; // series instance UIDs, each once
};

// The bodies of the parts of an upload (views into `body`). Throws UploadError
// (415 for another content type, 400 for a broken multipart body).
std::vector<std::string_view> uploadParts(std::string_view contentType, std::string_view body);

// Checks every part (a DICOM Part 10 file with study, series and SOP instance
// UIDs), then adds them to the store at storeRoot. Throws UploadError naming
// the part and what is wrong (nothing stored then), or StoreError.
UploadSummary storeUpload(const std::filesystem::path& storeRoot, std::string_view contentType,
                          std::string_view body);

} // namespace lucent::remote
