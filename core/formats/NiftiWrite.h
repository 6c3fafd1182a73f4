#pragma once

#include <filesystem>

#include "core/volume/Volume.h"

namespace lucent {

// Writes a volume as a NIfTI-1 single file (.nii, or gzipped when the name ends in .gz):
// int16, uint16 or float32 as the volume holds them, the geometry as the sform (and
// sform_code 2, aligned) in NIfTI's RAS, spacing in pixdim, mm units. The file appears
// complete or not at all. Throws std::runtime_error naming the file on failure.
// readNifti reads it back to the same voxels and geometry (float precision).
void writeNifti(const std::filesystem::path& path, const Volume& volume);

} // namespace lucent
