#pragma once
// The 3D view tests' volume: a soft-edged ball.

#include <algorithm>
#include <memory>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent::test {

// A ball of 1000 (radius 10 voxels) in a 32^3 volume of 0.
inline std::shared_ptr<const Volume> makeBall() {
    VolumeGeometry g;
    g.dims = {32, 32, 32};
    auto volume = std::make_shared<Volume>(g, VoxelType::Int16);
    auto voxels = volume->voxels<std::int16_t>();
    for (int k = 0; k < 32; ++k) {
        for (int j = 0; j < 32; ++j) {
            for (int i = 0; i < 32; ++i) {
                const double r = glm::length(glm::dvec3(i, j, k) - glm::dvec3(15.5));
                voxels[volume->linearIndex(i, j, k)] =
                    static_cast<std::int16_t>(std::clamp((11.0 - r) / 2.0, 0.0, 1.0) * 1000.0);
            }
        }
    }
    volume->modality = "CT";
    return volume;
}

} // namespace lucent::test
