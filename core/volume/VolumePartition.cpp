#include "core/volume/VolumePartition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lucent {

BrickTable BrickTable::of(const BrickGrid& grid) {
    BrickTable t;
    t.dims = grid.volumeDims();
    t.brickSize = grid.brickSize();
    t.perAxis = grid.bricksPerAxis();
    t.range.reserve(grid.count());
    for (const Brick& b : grid.bricks()) {
        t.range.emplace_back(b.minValue, b.maxValue);
    }
    return t;
}

VolumePartition::VolumePartition(const BrickTable& bricks, glm::dvec3 spacing, int parts,
                                 const std::function<bool(double lo, double hi)>& isVisible,
                                 int preferredAxis)
    : dims_(bricks.dims), brickSize_(bricks.brickSize) {
    const std::size_t count = std::size_t(bricks.perAxis.x) * bricks.perAxis.y * bricks.perAxis.z;
    if (bricks.range.size() != count || bricks.brickSize < 1) {
        throw std::invalid_argument("brick table: " + std::to_string(bricks.range.size()) +
                                    " ranges for " + std::to_string(count) + " bricks");
    }
    if (parts < 1) {
        throw std::invalid_argument("a volume splits into at least 1 part, not " +
                                    std::to_string(parts));
    }
    if (count < std::size_t(parts)) {
        throw std::invalid_argument(std::to_string(parts) + " parts (ranks) for a volume of " +
                                    std::to_string(count) + " bricks of " +
                                    std::to_string(bricks.brickSize) +
                                    " voxels: use at most as many ranks as bricks, or "
                                    "smaller bricks");
    }
    std::vector<double> weight(count);
    for (std::size_t i = 0; i < count; ++i) {
        const glm::vec2 r = bricks.range[i];
        weight[i] = isVisible(double(r.x), double(r.y)) ? 1.0 : kHiddenBrickWeight;
    }
    boxes_.resize(std::size_t(parts));
    weights_.assign(std::size_t(parts), 0.0);
    build(bricks, spacing, glm::ivec3(0), bricks.perAxis, parts, weight, preferredAxis);
}

// Bricks [lo, hi) (brick indices) into `parts` parts; returns the node.
int VolumePartition::build(const BrickTable& bricks, glm::dvec3 spacing, glm::ivec3 lo,
                           glm::ivec3 hi, int parts, const std::vector<double>& brickWeight,
                           int preferredAxis) {
    const int self = int(nodes_.size());
    nodes_.emplace_back();
    auto weightOf = [&](glm::ivec3 a, glm::ivec3 b) {
        double w = 0.0;
        for (int k = a.z; k < b.z; ++k) {
            for (int j = a.y; j < b.y; ++j) {
                for (int i = a.x; i < b.x; ++i) {
                    w += brickWeight[std::size_t(i) +
                                     std::size_t(bricks.perAxis.x) *
                                         (std::size_t(j) + std::size_t(bricks.perAxis.y) * k)];
                }
            }
        }
        return w;
    };
    if (parts == 1) {
        // The lowest part index not yet given: leaves are numbered in build order.
        const int part = int(
            std::count_if(nodes_.begin(), nodes_.end(), [](const Node& n) { return n.part >= 0; }));
        nodes_[std::size_t(self)].part = part;
        PartBox& box = boxes_[std::size_t(part)];
        box.lo = lo * bricks.brickSize;
        for (int a = 0; a < 3; ++a) {
            box.hi[a] = hi[a] == bricks.perAxis[a] ? bricks.dims[a] - 1 : hi[a] * bricks.brickSize;
        }
        weights_[std::size_t(part)] = weightOf(lo, hi);
        return self;
    }
    const int lowerParts = parts / 2, upperParts = parts - lowerParts;
    const glm::ivec3 extent = hi - lo;
    // Axes by length in millimetres, longest first; an axis of one brick cannot be cut.
    int axes[3] = {0, 1, 2};
    std::sort(axes, axes + 3, [&](int a, int b) {
        const double la =
            double(std::min(hi[a] * bricks.brickSize, bricks.dims[a]) - lo[a] * bricks.brickSize) *
            spacing[a];
        const double lb =
            double(std::min(hi[b] * bricks.brickSize, bricks.dims[b]) - lo[b] * bricks.brickSize) *
            spacing[b];
        return la > lb || (la == lb && a < b);
    });
    // The cut that makes the heavier half's weight per part smallest, over
    // all axes; on a tie the longer axis (compact boxes composite cheaper).
    int axis = -1, cut = 0;
    double best = std::numeric_limits<double>::infinity();
    double bestPreferred = best;
    int cutPreferred = 0;
    for (int a : axes) {
        // Each half needs at least as many bricks as parts, and a width: a cut
        // at the last voxel would leave a box of no thickness.
        const long slab = long(extent.x) * extent.y * extent.z / extent[a];
        for (int c = lo[a] + 1; c < hi[a]; ++c) {
            if (long(c - lo[a]) * slab < lowerParts || long(hi[a] - c) * slab < upperParts ||
                c * bricks.brickSize >= bricks.dims[a] - 1) {
                continue;
            }
            glm::ivec3 mid = hi;
            mid[a] = c;
            glm::ivec3 midLo = lo;
            midLo[a] = c;
            const double heavier =
                std::max(weightOf(lo, mid) / lowerParts, weightOf(midLo, hi) / upperParts);
            if (heavier < best * (1.0 - 1e-9)) {
                best = heavier;
                axis = a;
                cut = c;
            }
            if (a == preferredAxis && heavier < bestPreferred * (1.0 - 1e-9)) {
                bestPreferred = heavier;
                cutPreferred = c;
            }
        }
    }
    if (std::isfinite(bestPreferred) && bestPreferred <= kPreferredSlack * best) {
        axis = preferredAxis;
        cut = cutPreferred;
    }
    if (axis < 0) {
        throw std::invalid_argument("no cut of bricks " + std::to_string(lo.x) + ".." +
                                    std::to_string(hi.x - 1) + ", " + std::to_string(lo.y) + ".." +
                                    std::to_string(hi.y - 1) + ", " + std::to_string(lo.z) + ".." +
                                    std::to_string(hi.z - 1) + " into " + std::to_string(parts) +
                                    " parts: use fewer ranks or smaller bricks");
    }
    glm::ivec3 mid = hi, midLo = lo;
    mid[axis] = cut;
    midLo[axis] = cut;
    const int lower = build(bricks, spacing, lo, mid, lowerParts, brickWeight, preferredAxis);
    const int upper = build(bricks, spacing, midLo, hi, upperParts, brickWeight, preferredAxis);
    Node& node = nodes_[std::size_t(self)];
    node.axis = axis;
    node.plane = cut * bricks.brickSize;
    node.lower = lower;
    node.upper = upper;
    return self;
}

std::vector<int> VolumePartition::frontToBack(const glm::dvec3& eye) const {
    std::vector<int> out;
    out.reserve(boxes_.size());
    order(0, eye, out);
    return out;
}

void VolumePartition::order(int node, const glm::dvec3& eye, std::vector<int>& out) const {
    const Node& n = nodes_[std::size_t(node)];
    if (n.axis < 0) {
        out.push_back(n.part);
        return;
    }
    // The child on the eye's side of the cut is in front of the other.
    const bool lowerFirst = eye[n.axis] < double(n.plane);
    order(lowerFirst ? n.lower : n.upper, eye, out);
    order(lowerFirst ? n.upper : n.lower, eye, out);
}

} // namespace lucent
