#pragma once

#include <string>
#include <vector>

#include "core/volume/Volume.h"

namespace lucent {

// What a volume file says about its volume, read without the voxels.
struct VolumeFileHeader {
    VolumeGeometry geometry;
    VoxelType voxelType = VoxelType::Int16; // the type the full read returns
    std::string modality;                   // "CT", "MR", ... or empty when unknown
    std::string description;
    std::vector<std::string> warnings;
};

} // namespace lucent
