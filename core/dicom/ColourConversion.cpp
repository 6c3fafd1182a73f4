#include "core/dicom/ColourConversion_p.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/dicom/PixelConversion.h"
#include "core/io/LoadControl.h"

namespace lucent {
namespace {

std::uint8_t clampByte(double v) {
    return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

// PS3.3 C.7.6.3.1.2: YBR_FULL is JPEG's full-range YCbCr (ITU-R BT.601).
void ybrToRgb(int y, int cb, int cr, std::uint8_t* rgb) {
    rgb[0] = clampByte(y + 1.402 * (cr - 128));
    rgb[1] = clampByte(y - 0.344136 * (cb - 128) - 0.714136 * (cr - 128));
    rgb[2] = clampByte(y + 1.772 * (cb - 128));
}

} // namespace

void colourFrameToRgb(const std::string& file, const char* src, int columns, int rows,
                      const std::string& photometric, int planar, std::uint8_t* dst) {
    const auto* s = reinterpret_cast<const std::uint8_t*>(src);
    const std::size_t n = static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
    // The i-th pixel's sample c, in either planar configuration.
    const auto sample = [&](std::size_t i, int c) {
        return planar == 1 ? s[static_cast<std::size_t>(c) * n + i]
                           : s[3 * i + static_cast<std::size_t>(c)];
    };
    if (photometric == "RGB") {
        for (std::size_t i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c) {
                dst[3 * i + static_cast<std::size_t>(c)] = sample(i, c);
            }
        }
        return;
    }
    if (photometric == "YBR_FULL" || photometric == "YBR_ICT") {
        for (std::size_t i = 0; i < n; ++i) {
            ybrToRgb(sample(i, 0), sample(i, 1), sample(i, 2), dst + 3 * i);
        }
        return;
    }
    if (photometric == "YBR_FULL_422") {
        // Y1 Y2 Cb Cr for every two pixels of a row (the standard asks for even columns).
        if (columns % 2 != 0) {
            throw LoadError(file + ": YBR_FULL_422 with an odd number of columns (" +
                            std::to_string(columns) + ")");
        }
        for (std::size_t i = 0; i < n; i += 2) {
            const std::uint8_t* g = s + 2 * i;
            ybrToRgb(g[0], g[2], g[3], dst + 3 * i);
            ybrToRgb(g[1], g[2], g[3], dst + 3 * (i + 1));
        }
        return;
    }
    throw LoadError(file + ": PhotometricInterpretation " + photometric +
                    " cannot be converted to RGB");
}

void paletteFrameToRgb(const char* src, std::size_t n, const RawFormat& format,
                       const PaletteTable& palette, std::uint8_t* dst) {
    std::vector<float> index(n);
    convertFrame(src, n, format, 1.0, 0.0, index.data());
    for (std::size_t i = 0; i < n; ++i) {
        palette.colourOf(static_cast<std::int64_t>(index[i]), dst + 3 * i);
    }
}

} // namespace lucent
