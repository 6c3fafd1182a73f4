#pragma once

// Internal to core/formats: a forward-only reader of .tar.gz (or plain .tar)
// archives, enough for project files. libarchive does the reading (its tar
// format and gzip filter only); this class keeps the limits a project needs.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>

namespace lucent::formats {

class TarGzReader {
public:
    struct Entry {
        std::string name; // path inside the archive
        std::uint64_t size = 0;
    };

    // Longest entry name accepted (GNU long names and pax paths included).
    static constexpr std::size_t maxNameBytes = std::size_t{1} << 20;

    // Throws LoadError when the file cannot be opened.
    explicit TarGzReader(const std::filesystem::path& archive);
    ~TarGzReader();
    TarGzReader(const TarGzReader&) = delete;
    TarGzReader& operator=(const TarGzReader&) = delete;

    // Moves to the next regular file, skipping what is left of the current one
    // and every other kind of entry (directories, links, sparse files, ...).
    // Returns nullopt at the end of the archive. Throws LoadError on a damaged
    // archive, naming the file (and the entry, once one was read).
    std::optional<Entry> next();

    // Reads from the current entry; returns fewer bytes only at its end.
    std::size_t read(std::span<std::byte> dst);

private:
    [[noreturn]] void fail(const std::string& what) const;

    struct Archive;
    std::unique_ptr<Archive> archive_;
    std::string file_;
    std::string entry_;      // name of the current entry, for messages
    std::uint64_t left_ = 0; // bytes of the current entry not yet read
};

} // namespace lucent::formats
