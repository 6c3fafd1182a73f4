#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lucent {

// An 8-bit RGBA image: pixels row-major, top row first, 4 bytes per pixel
// (R, G, B, A), no padding between rows.
struct ImageRGBA8 {
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels;

    // A width x height image with every byte set to `fill` (an aggregate
    // otherwise). Throws std::invalid_argument for a negative size.
    static ImageRGBA8 filled(int width, int height, std::uint8_t fill = 0);

    bool empty() const { return width <= 0 || height <= 0; }
    std::size_t pixelCount() const {
        return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    }
    // Index of pixel (x, y)'s first byte (R) in `pixels`.
    std::size_t offset(int x, int y) const {
        return 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                    static_cast<std::size_t>(x));
    }
    // Pointer to pixel (x, y)'s four bytes R, G, B, A. No bounds check.
    std::uint8_t* at(int x, int y) { return pixels.data() + offset(x, y); }
    const std::uint8_t* at(int x, int y) const { return pixels.data() + offset(x, y); }
    // One channel (0 R, 1 G, 2 B, 3 A) of pixel (x, y). No bounds check.
    std::uint8_t& at(int x, int y, int channel) { return at(x, y)[channel]; }
    std::uint8_t at(int x, int y, int channel) const { return at(x, y)[channel]; }

    bool operator==(const ImageRGBA8&) const = default;
};

} // namespace lucent
