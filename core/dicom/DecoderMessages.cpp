#include "core/dicom/DecoderMessages.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <type_traits>

#include <sys/socket.h>
#include <unistd.h>

namespace lucent {

namespace {

constexpr std::uint32_t kMaxText = 1 << 16; // file names, syntaxes, error messages

bool writeAll(int fd, const void* data, std::size_t n) {
    const auto* p = static_cast<const char*>(data);
    while (n > 0) {
        // send() on the socket: MSG_NOSIGNAL so that a decoder gone does not
        // raise SIGPIPE in the application; write() where fd is no socket.
        ssize_t k = ::send(fd, p, n, MSG_NOSIGNAL);
        if (k < 0 && errno == ENOTSOCK) {
            k = ::write(fd, p, n);
        }
        if (k < 0 && errno == EINTR) {
            continue;
        }
        if (k <= 0) {
            return false;
        }
        p += k;
        n -= static_cast<std::size_t>(k);
    }
    return true;
}

bool readAll(int fd, void* data, std::size_t n) {
    auto* p = static_cast<char*>(data);
    while (n > 0) {
        const ssize_t k = ::read(fd, p, n);
        if (k < 0 && errno == EINTR) {
            continue;
        }
        if (k <= 0) {
            return false;
        }
        p += k;
        n -= static_cast<std::size_t>(k);
    }
    return true;
}

template <class T> bool put(int fd, T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    return writeAll(fd, &value, sizeof value);
}

template <class T> bool get(int fd, T& value) {
    return readAll(fd, &value, sizeof value);
}

bool putText(int fd, const std::string& text) {
    const auto n = static_cast<std::uint32_t>(std::min<std::size_t>(text.size(), kMaxText));
    return put(fd, n) && writeAll(fd, text.data(), n);
}

bool getText(int fd, std::string& text) {
    std::uint32_t n = 0;
    if (!get(fd, n) || n > kMaxText) {
        return false;
    }
    text.resize(n);
    return readAll(fd, text.data(), n);
}

struct LayoutFields {
    std::int32_t rows, columns, bitsAllocated, bitsStored, highBit, isSigned, frames;
    std::int32_t samplesPerPixel, planarConfiguration;
};

} // namespace

bool writeRequest(int fd, const DecodeRequest& r) {
    const PixelLayout& l = r.layout;
    const LayoutFields f{l.rows,       l.columns,         l.bitsAllocated,
                         l.bitsStored, l.highBit,         l.isSigned ? 1 : 0,
                         r.frames,     l.samplesPerPixel, l.planarConfiguration};
    return putText(fd, r.file) && putText(fd, l.transferSyntax) && putText(fd, l.photometric) &&
           put(fd, f);
}

std::optional<DecodeRequest> readRequest(int fd) {
    DecodeRequest r;
    LayoutFields f{};
    if (!getText(fd, r.file) || !getText(fd, r.layout.transferSyntax) ||
        !getText(fd, r.layout.photometric) || !get(fd, f) || f.samplesPerPixel < 1 ||
        f.samplesPerPixel > 4) {
        return std::nullopt;
    }
    r.layout.samplesPerPixel = f.samplesPerPixel;
    r.layout.planarConfiguration = f.planarConfiguration;
    r.layout.rows = f.rows;
    r.layout.columns = f.columns;
    r.layout.bitsAllocated = f.bitsAllocated;
    r.layout.bitsStored = f.bitsStored;
    r.layout.highBit = f.highBit;
    r.layout.isSigned = f.isSigned != 0;
    r.frames = f.frames;
    return r;
}

bool writeReply(int fd, const DecodeReply& reply) {
    if (const auto* why = std::get_if<std::string>(&reply)) {
        return put(fd, std::uint8_t{0}) && putText(fd, *why);
    }
    const DecodedFrames& d = std::get<DecodedFrames>(reply);
    const LayoutFields f{0,
                         0,
                         d.format.bitsAllocated,
                         d.format.bitsStored,
                         d.format.highBit,
                         d.format.isSigned ? 1 : 0,
                         0,
                         1,
                         d.planarConfiguration};
    return put(fd, std::uint8_t{1}) && put(fd, f) && putText(fd, d.photometric) &&
           put(fd, static_cast<std::uint64_t>(d.frameBytes)) &&
           put(fd, static_cast<std::uint64_t>(d.buffer.size())) &&
           writeAll(fd, d.buffer.data(), d.buffer.size());
}

std::optional<DecodeReply> readReply(int fd, std::size_t maxBytes) {
    std::uint8_t ok = 0;
    if (!get(fd, ok)) {
        return std::nullopt;
    }
    if (ok == 0) {
        std::string why;
        return getText(fd, why) ? std::optional<DecodeReply>(why) : std::nullopt;
    }
    LayoutFields f{};
    std::uint64_t frameBytes = 0;
    std::uint64_t size = 0;
    DecodedFrames d;
    if (!get(fd, f) || !getText(fd, d.photometric) || !get(fd, frameBytes) || !get(fd, size) ||
        size > maxBytes || frameBytes > size) {
        return std::nullopt;
    }
    d.planarConfiguration = f.planarConfiguration;
    d.format = {f.bitsAllocated, f.bitsStored, f.highBit, f.isSigned != 0};
    d.frameBytes = static_cast<std::size_t>(frameBytes);
    d.buffer.resize(static_cast<std::size_t>(size));
    if (!readAll(fd, d.buffer.data(), d.buffer.size())) {
        return std::nullopt;
    }
    return d;
}

} // namespace lucent
