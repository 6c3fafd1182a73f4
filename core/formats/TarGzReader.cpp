#include "core/formats/TarGzReader.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <vector>

#include <zlib.h>

#include "core/io/LoadControl.h"

namespace lucent::formats {

namespace {

constexpr std::size_t block = 512;

using Block = std::array<std::byte, block>;

std::string field(const Block& b, std::size_t offset, std::size_t size) {
    const char* p = reinterpret_cast<const char*>(b.data()) + offset;
    return std::string(p, std::find(p, p + size, '\0'));
}

// Octal number (possibly space or NUL terminated) or GNU base-256.
std::optional<std::uint64_t> number(const Block& b, std::size_t offset, std::size_t size) {
    const auto* p = reinterpret_cast<const unsigned char*>(b.data()) + offset;
    if (p[0] & 0x80) {
        std::uint64_t v = p[0] & 0x7f;
        for (std::size_t i = 1; i < size; ++i) {
            if (v >> 55) {
                return std::nullopt;
            }
            v = (v << 8) | p[i];
        }
        return v;
    }
    std::uint64_t v = 0;
    std::size_t i = 0;
    while (i < size && p[i] == ' ') {
        ++i;
    }
    for (; i < size && p[i] >= '0' && p[i] <= '7'; ++i) {
        v = v * 8 + (p[i] - '0');
    }
    for (; i < size; ++i) {
        if (p[i] != ' ' && p[i] != '\0') {
            return std::nullopt;
        }
    }
    return v;
}

bool checksumMatches(const Block& b) {
    const auto stored = number(b, 148, 8);
    if (!stored) {
        return false;
    }
    std::uint64_t unsignedSum = 0;
    std::int64_t signedSum = 0;
    for (std::size_t i = 0; i < block; ++i) {
        const bool inField = i >= 148 && i < 156;
        const auto u = inField ? static_cast<unsigned char>(' ') : static_cast<unsigned char>(b[i]);
        unsignedSum += u;
        signedSum += static_cast<signed char>(u);
    }
    return *stored == unsignedSum || static_cast<std::int64_t>(*stored) == signedSum;
}

// The "path" record of a pax extended header, if any.
std::optional<std::string> paxPath(const std::string& data) {
    std::size_t pos = 0;
    while (pos < data.size()) {
        const std::size_t space = data.find(' ', pos);
        if (space == std::string::npos) {
            break;
        }
        const std::size_t length = std::strtoull(data.c_str() + pos, nullptr, 10);
        if (length == 0 || pos + length > data.size()) {
            break;
        }
        const std::string record = data.substr(space + 1, pos + length - space - 2);
        if (record.starts_with("path=")) {
            return record.substr(5);
        }
        pos += length;
    }
    return std::nullopt;
}

} // namespace

struct TarGzReader::Gz {
    gzFile file = nullptr;
    ~Gz() {
        if (file) {
            gzclose(file);
        }
    }
};

TarGzReader::TarGzReader(const std::filesystem::path& archive)
    : gz_(std::make_unique<Gz>()), file_(archive.string()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(archive, ec)) {
        throw LoadError(file_ + ": no such file");
    }
    gz_->file = gzopen(file_.c_str(), "rb");
    if (!gz_->file) {
        throw LoadError(file_ + ": cannot open");
    }
    gzbuffer(gz_->file, 1 << 17);
}

TarGzReader::~TarGzReader() = default;

void TarGzReader::readExactly(std::span<std::byte> dst, const char* what) {
    std::size_t done = 0;
    while (done < dst.size()) {
        const auto n = static_cast<unsigned>(std::min<std::size_t>(dst.size() - done, 1u << 30));
        const int got = gzread(gz_->file, dst.data() + done, n);
        if (got < 0) {
            int code = 0;
            throw LoadError(file_ + ": damaged archive (" + gzerror(gz_->file, &code) + ")");
        }
        if (got == 0) {
            throw LoadError(file_ + ": archive ends inside " + what);
        }
        done += static_cast<std::size_t>(got);
    }
}

void TarGzReader::skip(std::uint64_t bytes) {
    std::array<std::byte, 1 << 16> scratch;
    while (bytes > 0) {
        const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(bytes, scratch.size()));
        readExactly(std::span(scratch).first(n), "an entry");
        bytes -= n;
    }
}

std::optional<TarGzReader::Entry> TarGzReader::next() {
    skip(left_ + padding_);
    left_ = padding_ = 0;
    std::optional<std::string> longName;
    for (;;) {
        Block b{};
        const int got = gzread(gz_->file, b.data(), block);
        if (got == 0 ||
            std::all_of(b.begin(), b.end(), [](std::byte x) { return x == std::byte{0}; })) {
            return std::nullopt; // end of archive (a zero block, or a missing end marker)
        }
        if (got != static_cast<int>(block) || !checksumMatches(b)) {
            throw LoadError(file_ + ": not a tar archive or damaged (bad header block)");
        }
        const auto size = number(b, 124, 12);
        if (!size) {
            throw LoadError(file_ + ": damaged tar header (size field)");
        }
        const std::uint64_t pad = (block - *size % block) % block;
        const char type = static_cast<char>(b[156]);
        if (type == 'L' || type == 'x') { // GNU long name or pax header for the next entry
            if (*size > (1u << 20)) {
                throw LoadError(file_ + ": implausible long-name record");
            }
            std::string data(static_cast<std::size_t>(*size), '\0');
            readExactly(std::as_writable_bytes(std::span(data)), "a long name");
            skip(pad);
            if (type == 'L') {
                longName = std::string(data.c_str());
            } else if (auto path = paxPath(data)) {
                longName = *path;
            }
            continue;
        }
        if (type != '0' && type != '\0' && type != '7') { // directories, links, ...
            skip(*size + pad);
            longName.reset();
            continue;
        }
        Entry e;
        e.size = *size;
        if (longName) {
            e.name = *longName;
        } else {
            // POSIX ustar has a name prefix; old GNU headers keep other data there.
            const bool posix = field(b, 257, 6) == "ustar";
            const std::string prefix = posix ? field(b, 345, 155) : std::string();
            const std::string name = field(b, 0, 100);
            e.name = prefix.empty() ? name : prefix + "/" + name;
        }
        left_ = *size;
        padding_ = pad;
        return e;
    }
}

std::size_t TarGzReader::read(std::span<std::byte> dst) {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(dst.size(), left_));
    if (n == 0) {
        return 0;
    }
    readExactly(dst.first(n), "an entry");
    left_ -= n;
    return n;
}

} // namespace lucent::formats
