#pragma once
// Grow from seeds: voxels painted for two or more segments grow into a full segmentation of
// the volume (or of a box around the seeds), the Segment Editor's "Grow from seeds".
//
// The algorithm is the improved, fast GrowCut of
//   L. Zhu, I. Kolesov, Y. Gao, R. Kikinis, A. Tannenbaum, "An Effective Interactive Medical
//   Image Segmentation Method Using Fast GrowCut", MICCAI 2014 Workshop on Interactive
//   Medical Image Computing (IMIC); journal version Gao et al., Sci Rep 14:29878, 2024,
// which 3D Slicer implements: each voxel takes the label of the seed nearest to it, the
// distance being the shortest path over face neighbours with the intensity difference
// |I(p) - I(q)| as the length of each step (Dijkstra). After a stroke only the voxels the new
// seeds come nearer to are visited, starting from the previous result (the paper's adaptive
// Dijkstra).
//
// Ties are broken the same way in both: a voxel at equal distance from seeds of two segments
// takes the segment given first. The result is then the unique lexicographic minimum of
// (distance, segment order) over all seeds, so an update equals a full computation from all
// the seeds voxel for voxel (tests/core/segmentation/test_grow_from_seeds.cpp checks it).
// Intensities are integers (CT's HU) and distances integer sums, so the queue is a bucket
// queue (Dial's algorithm) with no floating-point ties; float volumes are first mapped onto
// 0..4095 linearly, and any volume onto fewer levels when levels x segments would pass 2^20
// buckets (CT's 4096 levels: beyond 256 segments). Cells lie in bricks of 8^3 for the cache.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/segmentation/SegmentMask.h"
#include "core/volume/Volume.h"

namespace lucent {

// Voxel indices, lo inclusive, hi exclusive.
struct VoxelBox {
    glm::ivec3 lo{0};
    glm::ivec3 hi{0};
    bool operator==(const VoxelBox&) const = default;
    bool contains(const glm::ivec3& v) const {
        return glm::all(glm::greaterThanEqual(v, lo)) && glm::all(glm::lessThan(v, hi));
    }
    std::size_t voxelCount() const;
};

struct GrowOptions {
    // The region grown: the box around every seed padded by this many mm on each side
    // (Slicer's default keeps to the seeds' neighbourhood too); 0 or less: the whole volume.
    double roiMarginMm = 0.0;
};

struct GrowOutcome {
    bool incremental = false;      // started from the previous result
    std::size_t voxelsSettled = 0; // voxels whose label or distance was (re)computed
    double ms = 0.0;
};

class SeedGrower {
public:
    // The volume must outlive the grower (its intensities inside the box are copied at each
    // full computation).
    explicit SeedGrower(const Volume& volume, const GrowOptions& options = {});

    // Grows `seeds` (one mask per segment, on the volume's grid; at least two, at most 254):
    // from the previous result when the seeds only gained voxels and still lie in the box of
    // the previous call, else afresh. std::invalid_argument for fewer than two segments, a
    // mask on another grid or no seed voxel at all.
    GrowOutcome grow(std::span<const SegmentMask> seeds);
    // Forgets the previous result: the next grow() computes afresh.
    void reset();

    // The grown segments on the volume's grid, in the order of the seeds; empty outside the
    // box. Kept up to date by grow() (an update changes the voxels it relabelled alone).
    const std::vector<SegmentMask>& masks() const { return masks_; }
    const VoxelBox& box() const { return box_; }

private:
    bool canUpdate(std::span<const SegmentMask> seeds, const VoxelBox& box) const;
    void prepare(const VoxelBox& box, std::size_t segments);
    std::size_t propagate(std::span<const SegmentMask> seeds);
    std::size_t padded(const glm::ivec3& v) const; // the cell of a volume voxel
    glm::ivec3 voxelOfCell(std::size_t cell) const;
    void rebuildMasks();

    const Volume& volume_;
    GrowOptions options_;
    VoxelBox box_;
    glm::ivec3 bricks_{0}; // of 8 x 8 x 8 cells over the box and its layer
    std::size_t segments_ = 0;
    std::uint32_t maxStep_ = 0; // the largest intensity difference in the box
    // Each voxel of the box and a layer round it, in one place for the cache: its key,
    // distance * segments + segment (kUnreached before it is reached; 0 on the layer, which
    // no path can lower, so it needs no bounds checks), and its intensity minus the box's
    // minimum.
    struct Cell {
        std::uint32_t key;
        std::uint16_t value;
        std::uint8_t label; // key % segments, kept for the masks
    };
    std::vector<Cell> cells_;
    std::vector<std::uint32_t> relabelled_; // cells whose label the last call changed
    std::vector<SegmentMask> masks_;
    std::vector<SegmentMask> seeds_; // of the last call
};

// One full computation (SeedGrower::grow once): the grown segments in the order of `seeds`.
std::vector<SegmentMask> growFromSeeds(const Volume& volume, std::span<const SegmentMask> seeds,
                                       const GrowOptions& options = {});

} // namespace lucent
