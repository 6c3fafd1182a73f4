#pragma once
// A real greyscale image turned into an RLE single-frame RT dose, whole or with
// one flaw that GDCM's image helpers assert on (their assertions used to abort
// the whole process while loading). Written with DCMTK, not with the GDCM
// reader under test.

#include <string>

namespace lucent::test {

enum class RtDoseFlaw {
    None,           // a valid RT dose: one frame, one grid frame offset
    FrameCountAsUS, // Number of Frames (0028,0008) with VR US instead of IS
    FrameCountAsFD, // ... with VR FD
    NoGridOffsets,  // Grid Frame Offset Vector (3004,000C) empty
};

// Reads `source`, writes the RT dose to `path` (RLE Lossless) and returns `path`.
std::string writeRtDoseFromImage(const std::string& source, const std::string& path,
                                 RtDoseFlaw flaw);

} // namespace lucent::test
