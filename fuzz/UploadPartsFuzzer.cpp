// fuzz_upload_parts: one input is an upload (POST /studies): its first line is
// the Content-Type, the rest is the body. uploadParts splits it into DICOM
// parts or refuses it with an UploadError (400 or 415); each part it returns
// must lie inside the body.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "server/UploadParts.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lucent::remote;
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    const std::size_t lineEnd = input.find('\n');
    const std::string_view contentType = input.substr(0, lineEnd);
    const std::string_view body =
        lineEnd == std::string_view::npos ? std::string_view() : input.substr(lineEnd + 1);
    try {
        for (const std::string_view part : uploadParts(contentType, body)) {
            if (part.data() < body.data() ||
                part.data() + part.size() > body.data() + body.size()) {
                std::fprintf(stderr, "fuzz_upload_parts: a part lies outside the body\n");
                std::abort();
            }
        }
    } catch (const UploadError& e) {
        if (e.status() != 400 && e.status() != 415) {
            std::fprintf(stderr, "fuzz_upload_parts: refused with status %d\n", e.status());
            std::abort();
        }
    }
    return 0;
}
