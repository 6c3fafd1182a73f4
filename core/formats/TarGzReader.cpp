#include "core/formats/TarGzReader.h"

#include <algorithm>

#include <archive.h>
#include <archive_entry.h>

#include "core/io/LoadControl.h"

namespace lucent::formats {

namespace {

constexpr std::size_t readBlock = std::size_t{1} << 17;

// The entry's path as stored: the locale's bytes, or UTF-8 where those cannot
// be converted (pax paths in a C locale).
std::string entryName(archive_entry* e) {
    if (const char* name = archive_entry_pathname(e)) {
        return name;
    }
    if (const char* name = archive_entry_pathname_utf8(e)) {
        return name;
    }
    return {};
}

// Only plain files are project members. Hard links carry no data of their own;
// sparse files would expand holes into zeros (a cheap bomb), so they are skipped
// as the old reader skipped GNU 'S' entries.
bool isPlainFile(archive_entry* e) {
    return archive_entry_filetype(e) == AE_IFREG && archive_entry_hardlink(e) == nullptr &&
           archive_entry_sparse_count(e) == 0;
}

} // namespace

struct TarGzReader::Archive {
    archive* handle = archive_read_new();
    ~Archive() {
        if (handle) {
            archive_read_free(handle);
        }
    }
    std::string error() const {
        const char* text = archive_error_string(handle);
        return text ? text : "unknown error";
    }
};

TarGzReader::TarGzReader(const std::filesystem::path& path)
    : archive_(std::make_unique<Archive>()), file_(path.string()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw LoadError(file_ + ": no such file");
    }
    archive* a = archive_->handle;
    if (!a) {
        throw LoadError(file_ + ": cannot open (out of memory)");
    }
    // tar (ustar, pax, GNU) only, gzipped or not: no other format or filter is
    // reachable from a project file.
    if (archive_read_support_format_tar(a) != ARCHIVE_OK ||
        archive_read_support_filter_gzip(a) != ARCHIVE_OK) { // WARN: no zlib, an external gzip
        throw LoadError(file_ + ": cannot open (libarchive lacks tar or built-in gzip)");
    }
    if (archive_read_open_filename(a, file_.c_str(), readBlock) != ARCHIVE_OK) {
        throw LoadError(file_ + ": not a tar archive or damaged (" + archive_->error() + ")");
    }
}

TarGzReader::~TarGzReader() = default;

void TarGzReader::fail(const std::string& what) const {
    const std::string where = entry_.empty() ? "" : " after entry " + entry_;
    throw LoadError(file_ + ": " + what + where + " (" + archive_->error() + ")");
}

std::optional<TarGzReader::Entry> TarGzReader::next() {
    archive* a = archive_->handle;
    left_ = 0;
    for (;;) {
        archive_entry* e = nullptr;
        const int status = archive_read_next_header(a, &e); // skips the rest of the last entry
        if (status == ARCHIVE_EOF) {
            return std::nullopt;
        }
        if (status != ARCHIVE_OK && status != ARCHIVE_WARN) {
            fail("not a tar archive or damaged");
        }
        std::string name = entryName(e);
        if (name.size() > maxNameBytes) {
            throw LoadError(file_ + ": implausible entry name (" + std::to_string(name.size()) +
                            " bytes)");
        }
        entry_ = name;
        if (!isPlainFile(e)) {
            continue;
        }
        const la_int64_t size = archive_entry_size_is_set(e) ? archive_entry_size(e) : 0;
        if (size < 0) {
            throw LoadError(file_ + ": " + name + ": damaged tar header (negative size)");
        }
        left_ = static_cast<std::uint64_t>(size);
        return Entry{std::move(name), left_};
    }
}

std::size_t TarGzReader::read(std::span<std::byte> dst) {
    const auto wanted = static_cast<std::size_t>(std::min<std::uint64_t>(dst.size(), left_));
    std::size_t done = 0;
    while (done < wanted) {
        const la_ssize_t got =
            archive_read_data(archive_->handle, dst.data() + done, wanted - done);
        if (got < 0) {
            throw LoadError(file_ + ": " + entry_ + ": damaged archive (" + archive_->error() +
                            ")");
        }
        if (got == 0) {
            throw LoadError(file_ + ": " + entry_ + ": archive ends inside the entry (" +
                            std::to_string(left_ - done) + " bytes missing)");
        }
        done += static_cast<std::size_t>(got);
    }
    left_ -= done;
    return done;
}

} // namespace lucent::formats
