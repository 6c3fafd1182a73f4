#pragma once
// An image's colours reduced to a palette of at most 256 for GIF frames:
// median cut on a 6-bit-per-channel histogram, splitting the box of largest
// squared error along its widest-spread channel, then each colour mapped to
// its nearest palette entry. No dithering (dither noise costs PSNR and GIF size).

#include <array>
#include <cstdint>
#include <vector>

#include "core/image/Image.h"

namespace lucent {

struct PalettedImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> indices;                // row-major, one byte a pixel
    std::vector<std::array<std::uint8_t, 3>> palette; // RGB, 1 to 256 entries
};

// Alpha is ignored. Throws std::invalid_argument for an empty image.
PalettedImage quantizeToPalette(const ImageRGBA8& image, int maxColours = 256);

} // namespace lucent
