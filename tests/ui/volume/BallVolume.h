#pragma once
// The 3D view tests' volume: a soft-edged ball, and the transfer function that
// shows it opaque white on black.

#include <algorithm>
#include <memory>

#include <glm/glm.hpp>

#include "core/tf/TransferFunction.h"
#include "core/volume/Volume.h"

namespace lucent::test {

// A ball of 1000 (radius 10 voxels about the centre, unless given) in a 32^3
// volume of 0, its edge a 2-voxel ramp.
inline std::shared_ptr<const Volume> makeBall(const glm::dvec3& centre = glm::dvec3(15.5),
                                              double radius = 10.0) {
    VolumeGeometry g;
    g.dims = {32, 32, 32};
    auto volume = std::make_shared<Volume>(g, VoxelType::Int16);
    auto voxels = volume->voxels<std::int16_t>();
    for (int k = 0; k < 32; ++k) {
        for (int j = 0; j < 32; ++j) {
            for (int i = 0; i < 32; ++i) {
                const double r = glm::length(glm::dvec3(i, j, k) - centre);
                voxels[volume->linearIndex(i, j, k)] = static_cast<std::int16_t>(
                    std::clamp((radius + 1.0 - r) / 2.0, 0.0, 1.0) * 1000.0);
            }
        }
    }
    volume->modality = "CT";
    return volume;
}

// Opaque white from 600 up, nothing below 400, unshaded.
inline TransferFunction whiteBall() {
    TransferFunction tf;
    tf.name = "ball";
    tf.opacity = {{0.0, 0.0}, {400.0, 0.0}, {600.0, 1.0}};
    tf.colour = {{0.0, {1.0, 1.0, 1.0}}};
    tf.shading.enabled = false;
    return tf;
}

} // namespace lucent::test
