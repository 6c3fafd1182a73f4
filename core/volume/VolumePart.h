#pragma once
// One box of a volume rendered apart from the rest of it (one rank of a
// distributed render): the part's voxels are a Volume of their own, and this
// says where they sit in the whole volume and which box of it the part draws.

#include <utility>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {

// Boxes of the whole volume that parts draw. Coordinates are the whole
// volume's voxel-centre indices. On each axis the box is [lo, hi): the hi face
// belongs to the next box, so that boxes tile [0, dims - 1] and a sample on a
// shared face is taken once. Where hi is the volume's last voxel (dims - 1)
// the box is closed there.
struct PartBox {
    glm::ivec3 lo{0};
    glm::ivec3 hi{0};
    bool operator==(const PartBox&) const = default;
};

struct VolumePart {
    VolumeGeometry whole; // the whole volume's geometry
    glm::ivec3 offset{0}; // the whole volume's index of the part's voxel (0, 0, 0)
    PartBox owned;        // the box the part draws
    std::pair<double, double> valueRange{0.0, 0.0}; // the whole volume's smallest and largest value

    // Whether the hi face of the owned box on `axis` is shared with another part (open).
    bool sharedHi(int axis) const { return owned.hi[axis] < whole.dims[axis] - 1; }
};

// The voxels [first, last) a part holds: its owned box (with the voxel at hi,
// which samples just below hi read) grown by `halo` voxels on every side,
// clamped to the volume.
std::pair<glm::ivec3, glm::ivec3> partVoxels(const PartBox& owned, glm::ivec3 dims, int halo);

// The geometry of the voxels [first, ...) of `whole`: the same spacing and
// direction, the origin moved to voxel `first`; dims `dims`.
VolumeGeometry partGeometry(const VolumeGeometry& whole, glm::ivec3 first, glm::ivec3 dims);

// A copy of the voxels [first, last) of `whole`, with partGeometry. Throws
// std::invalid_argument naming the range when it is empty or leaves the volume.
Volume cutPart(const Volume& whole, glm::ivec3 first, glm::ivec3 last);

} // namespace lucent
