#pragma once
// What a 2D stack needs from a file's header beyond the scan's facts: the window,
// the cine timing, the palette. Private to lucent_io.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/stack/ImageStack.h"

namespace lucent {

// A palette colour lookup table (PS3.3 C.7.6.3.1.5), as 8-bit entries.
struct PaletteTable {
    int firstMapped = 0;                              // the stored value that maps to entry 0
    std::array<std::vector<std::uint8_t>, 3> entries; // red, green, blue
    bool empty() const { return entries[0].empty(); }
    // An index below the first entry takes the first, above the last the last.
    const std::uint8_t* colourOf(std::int64_t stored, std::uint8_t rgb[3]) const;
};

struct StackHeader {
    GreyWindow window;                   // WindowCenter/Width (0028,1050/1051), first values
    double frameTimeMs = 0.0;            // FrameTime (0018,1063)
    std::vector<double> frameTimeVector; // FrameTimeVector (0018,1065): ms from the previous frame
    PaletteTable palette;                // read when asked for
};

// Throws LoadError naming the file and the element when it cannot be read or a
// palette is asked for and is missing, segmented or inconsistent.
StackHeader readStackHeader(const std::string& file, bool palette);

} // namespace lucent
