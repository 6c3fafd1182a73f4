#include "core/exchange/ZipWriter.h"

#include <algorithm>
#include <memory>
#include <vector>

#include <zip.h>

#include "core/exchange/DicomExport.h"

namespace lucent {
namespace {

struct ZipDiscard {
    void operator()(zip_t* z) const { zip_discard(z); }
};

} // namespace

void zipFolder(const std::filesystem::path& folder, const std::filesystem::path& zipFile) {
    namespace fs = std::filesystem;
    int code = 0;
    std::unique_ptr<zip_t, ZipDiscard> zip(zip_open(zipFile.c_str(), ZIP_CREATE | ZIP_EXCL, &code));
    if (!zip) {
        zip_error_t error;
        zip_error_init_with_code(&error, code);
        const std::string why = zip_error_strerror(&error);
        zip_error_fini(&error);
        throw ExportError(zipFile.string() + ": cannot create the ZIP file (" + why + ")");
    }
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        if (entry.is_regular_file()) {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
        zip_source_t* source = zip_source_file(zip.get(), f.c_str(), 0, -1);
        const std::string name = f.lexically_relative(folder).generic_string();
        if (!source || zip_file_add(zip.get(), name.c_str(), source, ZIP_FL_ENC_UTF_8) < 0) {
            if (source) {
                zip_source_free(source);
            }
            throw ExportError(zipFile.string() + ": cannot add " + f.string() + " (" +
                              zip_strerror(zip.get()) + ")");
        }
    }
    // The files are read and compressed here; on success the archive is freed.
    if (zip_close(zip.get()) != 0) {
        throw ExportError(zipFile.string() + ": cannot write the ZIP file (" +
                          zip_strerror(zip.get()) + ")");
    }
    static_cast<void>(zip.release());
}

} // namespace lucent
