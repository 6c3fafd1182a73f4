#pragma once

#include <filesystem>

#include "core/formats/VolumeFileHeader.h"
#include "core/volume/Volume.h"

namespace lucent {

// MetaImage (ITK MetaIO): a text header (.mhd, or .mha with the voxels after
// it) and raw voxels. TransformMatrix lists the unit vector of the i axis
// first, then j, then k (ITK's convention). Element types: MET_SHORT -> Int16,
// MET_USHORT -> UInt16, MET_FLOAT -> Float32, MET_UCHAR/MET_CHAR -> Int16,
// MET_INT/MET_UINT/MET_DOUBLE -> Float32. Byte order, zlib compression,
// HeaderSize and LOCAL data are honoured. Throws LoadError naming the file.
VolumeFileHeader readMetaImageHeader(const std::filesystem::path& mhd);
Volume readMetaImage(const std::filesystem::path& mhd);
// Slices [k0, k1) of an uncompressed MetaImage, read from their byte range of
// the data file alone (a rank of a distributed render reads only its slab);
// the geometry's origin moves to slice k0. Throws LoadError naming the file,
// for compressed data too (no byte range per slice: metaImageHasSliceRanges).
Volume readMetaImageSlices(const std::filesystem::path& mhd, int k0, int k1);
bool metaImageHasSliceRanges(const std::filesystem::path& mhd);

// Writes mhd and, beside it, <stem>.raw (i fastest, little endian), each under a
// temporary name first, so that a failed write leaves no partial file. Throws
// std::runtime_error naming the file when writing fails.
void writeMetaImage(const Volume& v, const std::filesystem::path& mhd);

} // namespace lucent
