#pragma once
// Stored colour samples -> 8-bit RGB: RGB (either planar configuration), YBR_FULL,
// YBR_FULL_422 (uncompressed: two luminance samples share one chrominance pair),
// YBR_ICT (the same matrix), and palette colour through its table. Private to lucent_io.

#include <cstdint>
#include <string>

#include "core/dicom/FrameDecoder.h"
#include "core/dicom/StackHeader_p.h"

namespace lucent {

// One frame of columns x rows pixels in `photometric` with `planar` layout, 8 bits a
// sample, into dst (3 bytes a pixel). Throws LoadError naming the file for an
// interpretation it cannot convert.
void colourFrameToRgb(const std::string& file, const char* src, int columns, int rows,
                      const std::string& photometric, int planar, std::uint8_t* dst);

// One frame of n palette indices (stored values of `format`) into dst.
void paletteFrameToRgb(const char* src, std::size_t n, const RawFormat& format,
                       const PaletteTable& palette, std::uint8_t* dst);

} // namespace lucent
