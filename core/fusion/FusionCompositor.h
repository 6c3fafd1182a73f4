#pragma once
// A fused image: the base's pixels (already windowed, RGB) with the overlay's values
// drawn over them through a FusionStyle.

#include <cstdint>
#include <span>
#include <vector>

#include "core/fusion/FusionStyle.h"

namespace lucent {

// 0xffRRGGBB, as QImage::Format_RGB32 stores a pixel.
using Rgb32 = std::uint32_t;

inline constexpr Rgb32 rgb32(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    return 0xff000000u | (Rgb32(r) << 16) | (Rgb32(g) << 8) | Rgb32(b);
}
inline constexpr Rgb32 greyRgb32(std::uint8_t v) {
    return rgb32(v, v, v);
}

// Whether pixel (x, y) of a width-wide image shows the overlay (alone or blended) under
// the style's mode: Blend everywhere, Checkerboard on the odd squares (the square at
// the top-left is the base's), Swipe at x >= swipe * width.
bool showsOverlay(const FusionStyle& style, int x, int y, int width);

// The fused image, row-major width x height. `base` is the base's windowed image,
// `overlay` the overlay's values at the same pixels (NaN where it has none: the base
// shows). Blend: base * (1 - opacity) + colour * opacity per channel, rounded; with
// clearBelowWindow, values below center - width/2 leave the base. Checkerboard and
// Swipe: the colour itself where the overlay shows.
std::vector<Rgb32> composeFusion(std::span<const Rgb32> base, std::span<const float> overlay,
                                 int width, int height, const FusionStyle& style);

// Grey 8-bit pixels as RGB32 (a windowed MPR image as the base of composeFusion).
std::vector<Rgb32> greyToRgb32(std::span<const std::uint8_t> grey);

} // namespace lucent
