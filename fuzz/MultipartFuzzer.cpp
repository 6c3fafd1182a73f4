// fuzz_multipart: one input is a WADO-RS answer: its first line is the
// Content-Type, the next byte seeds the chunking, the rest is the body.
// MultipartStream (core/pacs) reads the body twice, in one piece and in chunks
// of random sizes, as the network hands it over: both must give the same parts,
// no part may hold the delimiter, each part must begin before its data and end
// once, and finish() must agree. The only refusal is a PacsError.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/pacs/MultipartStream.h"
#include "core/pacs/PacsNode.h"

namespace {

struct Outcome {
    std::vector<std::string> parts;
    int ended = 0;
    std::optional<std::string> error; // the PacsError of feed or finish
};

[[noreturn]] void found(const char* what) {
    std::fprintf(stderr, "fuzz_multipart: %s\n", what);
    std::abort();
}

// Chunk sizes from a small xorshift generator: mostly short, sometimes long.
class Chunker {
public:
    explicit Chunker(std::uint8_t seed) : state_(0x9e3779b9u ^ (seed * 0x01000193u)) {}
    std::size_t next() {
        state_ ^= state_ << 13;
        state_ ^= state_ >> 17;
        state_ ^= state_ << 5;
        return (state_ & 7) == 0 ? 1 + state_ % 4096 : 1 + (state_ >> 8) % 16;
    }

private:
    std::uint32_t state_;
};

Outcome parse(const QByteArray& contentType, std::string_view body, Chunker* chunker) {
    Outcome out;
    bool open = false;
    try {
        lucent::MultipartStream stream(contentType, "fuzz");
        stream.onPartBegin = [&] {
            if (open) {
                found("a part began before the last one ended");
            }
            open = true;
            out.parts.emplace_back();
        };
        stream.onPartData = [&](const char* data, qsizetype size) {
            if (!open || size <= 0) {
                found("part data outside a part, or empty");
            }
            out.parts.back().append(data, static_cast<std::size_t>(size));
        };
        stream.onPartEnd = [&] {
            if (!open) {
                found("a part ended that never began");
            }
            open = false;
            ++out.ended;
        };
        std::size_t at = 0;
        while (at < body.size()) {
            const std::size_t n =
                chunker ? std::min(chunker->next(), body.size() - at) : body.size() - at;
            stream.feed(body.data() + at, static_cast<qsizetype>(n));
            at += n;
        }
        if (stream.parts() != static_cast<int>(out.parts.size())) {
            found("parts() disagrees with the parts begun");
        }
        stream.finish();
    } catch (const lucent::PacsError& e) {
        out.error = e.what();
    }
    return out;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    const std::size_t lineEnd = input.find('\n');
    if (lineEnd == std::string_view::npos || lineEnd + 1 >= input.size()) {
        return 0;
    }
    const QByteArray contentType(input.data(), static_cast<qsizetype>(lineEnd));
    const auto seed = static_cast<std::uint8_t>(input[lineEnd + 1]);
    const std::string_view body = input.substr(lineEnd + 2);

    const Outcome whole = parse(contentType, body, nullptr);
    Chunker chunker(seed);
    const Outcome chunked = parse(contentType, body, &chunker);
    if (whole.parts != chunked.parts || whole.ended != chunked.ended ||
        whole.error.has_value() != chunked.error.has_value()) {
        found("the chunked body gave other parts than the whole body");
    }
    if (!whole.error && whole.ended != static_cast<int>(whole.parts.size())) {
        found("finished with a part left open");
    }
    // No part may hold the delimiter (CRLF "--" boundary) of the answer.
    const qsizetype b = contentType.indexOf("boundary=");
    if (b >= 0 && !whole.error) {
        QByteArray boundary = contentType.mid(b + 9);
        if (const qsizetype semicolon = boundary.indexOf(';'); semicolon >= 0) {
            boundary = boundary.left(semicolon);
        }
        boundary = boundary.trimmed();
        if (boundary.startsWith('"') && boundary.size() >= 2) {
            boundary = boundary.mid(1, boundary.size() - 2);
        }
        const std::string delimiter = "\r\n--" + boundary.toStdString();
        for (const std::string& part : whole.parts) {
            if (part.find(delimiter) != std::string::npos) {
                found("a part holds the delimiter");
            }
        }
    }
    return 0;
}
