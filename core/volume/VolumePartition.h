#pragma once
// How a volume is split among the parts (ranks) of a distributed render: a
// k-d split of its bricks, balanced by the bricks the transfer function makes
// visible, and the order in which the parts lie from front to back for an eye.

#include <cstddef>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/BrickGrid.h"
#include "core/volume/VolumePart.h"

namespace lucent {

// Every brick's value range, without the voxels: what the split weighs.
struct BrickTable {
    glm::ivec3 dims{0};           // the volume's voxels per axis
    int brickSize = 64;           // voxels per brick edge
    glm::ivec3 perAxis{0};        // bricks per axis
    std::vector<glm::vec2> range; // per brick id (x fastest): min, max over it and its overlap

    static BrickTable of(const BrickGrid& grid);
};

class VolumePartition {
public:
    // What a brick costs to draw: `visible` ones 1, the others (read, leapt over) this much.
    static constexpr double kHiddenBrickWeight = 1.0 / 16.0;

    // Splits the bricks among `parts` boxes, recursively: a box of n parts is
    // cut across its longest axis (in millimetres, given `spacing`) at the
    // brick boundary that best gives its halves n/2 and n - n/2 parts' worth of
    // weight. isVisible(lo, hi): whether a brick of that value range shows.
    // Throws std::invalid_argument when parts < 1 or the volume has fewer
    // bricks than parts (naming both counts).
    // preferredAxis (0, 1, 2; -1 for none): cut across it whenever such a cut
    // balances within kPreferredSlack of the best one. Parts read from DICOM
    // prefer k: a rank then reads only the slices of its slab.
    VolumePartition(const BrickTable& bricks, glm::dvec3 spacing, int parts,
                    const std::function<bool(double lo, double hi)>& isVisible,
                    int preferredAxis = -1);
    static constexpr double kPreferredSlack = 1.15;

    int parts() const { return int(boxes_.size()); }
    // The box part p draws (VolumePart.h: [lo, hi), closed at dims - 1).
    const PartBox& box(int part) const { return boxes_[std::size_t(part)]; }
    // The weight of part p's bricks (visible bricks count 1).
    double weight(int part) const { return weights_[std::size_t(part)]; }
    glm::ivec3 dims() const { return dims_; }

    // The parts from front to back for an eye at `eye` (the volume's index
    // coordinates): exact for any projection, since the boxes are the cells of
    // a binary space partition.
    std::vector<int> frontToBack(const glm::dvec3& eye) const;

private:
    struct Node {
        int axis = -1;              // -1: a leaf
        int plane = 0;              // voxel coordinate of the cut: lower child below it
        int lower = -1, upper = -1; // child nodes
        int part = -1;              // leaves: the part
    };
    int build(const BrickTable& bricks, glm::dvec3 spacing, glm::ivec3 lo, glm::ivec3 hi, int parts,
              const std::vector<double>& brickWeight, int preferredAxis);
    void order(int node, const glm::dvec3& eye, std::vector<int>& out) const;

    glm::ivec3 dims_{0};
    int brickSize_ = 64;
    std::vector<Node> nodes_;
    std::vector<PartBox> boxes_;
    std::vector<double> weights_;
};

} // namespace lucent
