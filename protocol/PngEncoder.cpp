#include "protocol/PngEncoder.h"

#include <zlib.h>

#include <stdexcept>
#include <vector>

namespace lucent::remote {
namespace {

void appendBigEndian(std::string& out, std::uint32_t value) {
    for (int shift : {24, 16, 8, 0}) {
        out.push_back(static_cast<char>((value >> shift) & 0xffu));
    }
}

void appendChunk(std::string& out, const char (&type)[5], const std::string& data) {
    appendBigEndian(out, static_cast<std::uint32_t>(data.size()));
    const std::size_t start = out.size();
    out.append(type, 4);
    out += data;
    const auto* bytes = reinterpret_cast<const Bytef*>(out.data() + start);
    appendBigEndian(
        out, static_cast<std::uint32_t>(crc32(0L, bytes, static_cast<uInt>(out.size() - start))));
}

// A PNG of filtered rows (each row: its filter byte, then the pixels) of `colourType`
// (0 grey, 2 RGB), 8 bits a sample.
std::string pngOfRows(const std::vector<std::uint8_t>& rows, int width, int height,
                      char colourType) {
    z_stream stream{};
    if (deflateInit2(&stream, 1, Z_DEFLATED, 15, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
        throw std::runtime_error("encodePng: zlib cannot start");
    }
    std::string compressed(deflateBound(&stream, static_cast<uLong>(rows.size())), '\0');
    stream.next_in = const_cast<Bytef*>(rows.data()); // zlib's API is not const
    stream.avail_in = static_cast<uInt>(rows.size());
    stream.next_out = reinterpret_cast<Bytef*>(compressed.data());
    stream.avail_out = static_cast<uInt>(compressed.size());
    const int status = deflate(&stream, Z_FINISH);
    compressed.resize(stream.total_out);
    deflateEnd(&stream);
    if (status != Z_STREAM_END) {
        throw std::runtime_error("encodePng: zlib failed");
    }
    std::string header;
    appendBigEndian(header, static_cast<std::uint32_t>(width));
    appendBigEndian(header, static_cast<std::uint32_t>(height));
    // 8 bits, the colour type, deflate, no filter method beyond the standard, no interlace
    header += std::string{'\x08', colourType, '\x00', '\x00', '\x00'};
    std::string png("\x89PNG\r\n\x1a\n", 8);
    appendChunk(png, "IHDR", header);
    appendChunk(png, "IDAT", compressed);
    appendChunk(png, "IEND", {});
    return png;
}

} // namespace

std::string encodePng(std::span<const std::uint8_t> rgba, int width, int height) {
    if (width < 1 || height < 1 || rgba.size() != std::size_t(width) * std::size_t(height) * 4) {
        throw std::invalid_argument("encodePng: the pixels do not match " + std::to_string(width) +
                                    " x " + std::to_string(height));
    }
    // Each row: filter type 0 (none), then RGB.
    const std::size_t rowBytes = 1 + 3 * std::size_t(width);
    std::vector<std::uint8_t> rows(rowBytes * std::size_t(height));
    for (int y = 0; y < height; ++y) {
        std::uint8_t* out = rows.data() + rowBytes * std::size_t(y);
        const std::uint8_t* in = rgba.data() + 4 * std::size_t(width) * std::size_t(y);
        *out++ = 0;
        for (int x = 0; x < width; ++x, in += 4) {
            *out++ = in[0];
            *out++ = in[1];
            *out++ = in[2];
        }
    }
    return pngOfRows(rows, width, height, '\x02');
}

std::string encodeGreyPng(std::span<const std::uint8_t> grey, int width, int height) {
    if (width < 1 || height < 1 || grey.size() != std::size_t(width) * std::size_t(height)) {
        throw std::invalid_argument("encodeGreyPng: the pixels do not match " +
                                    std::to_string(width) + " x " + std::to_string(height));
    }
    // Each row: filter type 1 (sub: the difference to the left neighbour), which
    // suits smooth grey slices.
    const std::size_t rowBytes = 1 + std::size_t(width);
    std::vector<std::uint8_t> rows(rowBytes * std::size_t(height));
    for (int y = 0; y < height; ++y) {
        std::uint8_t* out = rows.data() + rowBytes * std::size_t(y);
        const std::uint8_t* in = grey.data() + std::size_t(width) * std::size_t(y);
        out[0] = 1;
        out[1] = in[0];
        for (int x = 1; x < width; ++x) {
            out[1 + x] = static_cast<std::uint8_t>(in[x] - in[x - 1]);
        }
    }
    return pngOfRows(rows, width, height, '\x00');
}

} // namespace lucent::remote
