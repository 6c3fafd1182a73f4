#pragma once

#include <filesystem>

#include "core/formats/VolumeFileHeader.h"
#include "core/volume/Volume.h"

namespace lucent {

// InVesalius 3 projects (.inv3): a tar.gz holding <dir>/main.plist and the raw
// image matrix (numpy memmap, little endian, C order, shape (slices, rows, cols)).
//
// The project stores no patient coordinates. InVesalius keeps the DICOM column
// order, flips the rows (VTK's bottom-up convention) and stacks the slices from
// inferior to superior, so, with i = column, j = row, k = slice:
//   i runs right -> left      direction (+1, 0, 0)
//   j runs posterior -> anterior  direction (0, -1, 0)
//   k runs inferior -> superior   direction (0, 0, +1)
// (checked on the Cranium demo: teeth and nose at high rows, vertex at the last
// slices). The origin puts the centre of the volume at (0, 0, 0) LPS.
// Throws LoadError naming the file and the key or entry at fault.
VolumeFileHeader readInVesaliusHeader(const std::filesystem::path& inv3);
Volume readInVesalius(const std::filesystem::path& inv3);

} // namespace lucent
