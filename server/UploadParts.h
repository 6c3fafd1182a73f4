#pragma once
// The body of an upload (POST /studies) split into its DICOM parts: one
// application/dicom body, or the parts of a multipart/related one. Pure
// parsing, no sockets and no store: UploadIngest.h checks and stores the parts.

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

// The bodies of the parts of an upload (views into `body`). Throws UploadError
// (415 for another content type, 400 for a broken multipart body).
std::vector<std::string_view> uploadParts(std::string_view contentType, std::string_view body);

} // namespace lucent::remote
