#pragma once

// Internal to core/formats: a forward-only reader of .tar.gz (or plain .tar)
// archives, enough for project files: ustar headers, GNU long names, pax paths.

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

    // Throws LoadError when the file cannot be opened.
    explicit TarGzReader(const std::filesystem::path& archive);
    ~TarGzReader();
    TarGzReader(const TarGzReader&) = delete;
    TarGzReader& operator=(const TarGzReader&) = delete;

    // Moves to the next regular file, skipping what is left of the current one.
    // Returns nullopt at the end of the archive. Throws LoadError on a damaged
    // archive.
    std::optional<Entry> next();

    // Reads from the current entry; returns fewer bytes only at its end.
    std::size_t read(std::span<std::byte> dst);

private:
    void readExactly(std::span<std::byte> dst, const char* what);
    void skip(std::uint64_t bytes);

    struct Gz;
    std::unique_ptr<Gz> gz_;
    std::string file_;
    std::uint64_t left_ = 0;    // bytes of the current entry not yet read
    std::uint64_t padding_ = 0; // bytes after it up to the next 512-byte block
};

} // namespace lucent::formats
