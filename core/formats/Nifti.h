#pragma once

#include <filesystem>

#include "core/formats/VolumeFileHeader.h"
#include "core/volume/Volume.h"

namespace lucent {

// NIfTI-1 single-file images (.nii, and gzipped .nii.gz), either byte order.
// Geometry from the sform when sform_code > 0, else the qform, else pixdim
// alone (with a warning), converted from NIfTI's RAS to LPS. uint8/int8/int16
// load as Int16, uint16 as UInt16, the rest as Float32; scl_slope/scl_inter are
// applied (Float32 unless every stored value maps exactly to int16 or uint16).
// Of a 4D file only the first volume is read (with a warning).
// Throws LoadError naming the file and the problem.
VolumeFileHeader readNiftiHeader(const std::filesystem::path& path);
Volume readNifti(const std::filesystem::path& path);

} // namespace lucent
