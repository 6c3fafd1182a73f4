#include "core/segmentation/GrowFromSeeds.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lucent {
namespace {

constexpr std::uint32_t kUnreached = std::numeric_limits<std::uint32_t>::max();
constexpr std::size_t kMaxSegments = 254;
constexpr std::uint8_t kNoLabel = 0xff;
constexpr std::size_t kPrefetchAhead = 16; // queue entries
constexpr double kFloatLevels = 4095.0;    // float volumes are mapped onto 0..this
// The queue's ring holds (levels) x segments buckets: past this many, intensities are mapped
// onto fewer levels (more than 256 segments' worth of CT's 4096 levels).
constexpr double kMaxBuckets = double(1 << 20);

// The box of every seed voxel (empty hi == lo when there is none).
VoxelBox seedBounds(std::span<const SegmentMask> seeds) {
    glm::ivec3 lo(std::numeric_limits<int>::max()), hi(std::numeric_limits<int>::min());
    for (const SegmentMask& s : seeds) {
        s.forEachSet([&](std::size_t i) {
            const glm::ivec3 v = s.voxelOf(i);
            lo = glm::min(lo, v);
            hi = glm::max(hi, v + 1);
        });
    }
    return lo.x > hi.x ? VoxelBox{} : VoxelBox{lo, hi};
}

// Calls f(cell, voxel) for every cell of the bricks in storage order, voxel being the volume
// index of the voxel it holds or -1 on the padding.
template <class F>
void forEachCell(const glm::ivec3& bricks, const VoxelBox& box, const Volume& volume, F&& f) {
    const glm::ivec3 size = box.hi - box.lo;
    std::size_t cell = 0;
    for (int bz = 0; bz < bricks.z; ++bz) {
        for (int by = 0; by < bricks.y; ++by) {
            for (int bx = 0; bx < bricks.x; ++bx) {
                for (int lz = 0; lz < 8; ++lz) {
                    for (int ly = 0; ly < 8; ++ly) {
                        const int gz = bz * 8 + lz, gy = by * 8 + ly;
                        const bool row = gz >= 1 && gz <= size.z && gy >= 1 && gy <= size.y;
                        // The volume index of the (padding) cell at gx = 0: gx adds on.
                        std::ptrdiff_t first = 0;
                        if (row) {
                            first = std::ptrdiff_t(volume.linearIndex(box.lo.x, box.lo.y + gy - 1,
                                                                      box.lo.z + gz - 1)) -
                                    1;
                        }
                        for (int gx = bx * 8; gx < bx * 8 + 8; ++gx, ++cell) {
                            f(cell, row && gx >= 1 && gx <= size.x ? first + gx : -1);
                        }
                    }
                }
            }
        }
    }
}

} // namespace

std::size_t VoxelBox::voxelCount() const {
    const glm::ivec3 n = glm::max(hi - lo, glm::ivec3(0));
    return std::size_t(n.x) * std::size_t(n.y) * std::size_t(n.z);
}

SeedGrower::SeedGrower(const Volume& volume, const GrowOptions& options)
    : volume_(volume), options_(options) {}

void SeedGrower::reset() {
    seeds_.clear();
}

std::size_t SeedGrower::padded(const glm::ivec3& v) const {
    const glm::uvec3 g(v - box_.lo + 1);
    const std::size_t brick =
        (std::size_t(g.z >> 3) * std::size_t(bricks_.y) + (g.y >> 3)) * std::size_t(bricks_.x) +
        (g.x >> 3);
    return brick << 9 | ((g.z & 7u) << 6 | (g.y & 7u) << 3 | (g.x & 7u));
}

bool SeedGrower::canUpdate(std::span<const SegmentMask> seeds, const VoxelBox& bounds) const {
    if (seeds_.size() != seeds.size() || !box_.contains(bounds.lo) ||
        !box_.contains(bounds.hi - 1)) {
        return false;
    }
    // Only gained voxels: a seed taken away or moved needs the whole computation again.
    for (std::size_t s = 0; s < seeds.size(); ++s) {
        const auto before = seeds_[s].words(), now = seeds[s].words();
        for (std::size_t w = 0; w < before.size(); ++w) {
            if ((before[w] & ~now[w]) != 0) {
                return false;
            }
        }
    }
    return true;
}

void SeedGrower::prepare(const VoxelBox& box, std::size_t segments) {
    box_ = box;
    segments_ = segments;
    // The box and a layer round it, in bricks of 8 x 8 x 8 (each 4 kB): a voxel's six
    // neighbours mostly lie in its own brick, the queue's scattered visits in fewer pages.
    bricks_ = (box.hi - box.lo + 2 + 7) / 8;
    const std::size_t n =
        std::size_t(bricks_.x) * std::size_t(bricks_.y) * std::size_t(bricks_.z) * 512;
    cells_.assign(n, Cell{0, 0, 0});
    visitVoxels(volume_, [&](auto voxels) {
        using T = std::remove_cvref_t<decltype(voxels[0])>;
        T lo = std::numeric_limits<T>::max(), hi = std::numeric_limits<T>::lowest();
        for (int k = box.lo.z; k < box.hi.z; ++k) {
            for (int j = box.lo.y; j < box.hi.y; ++j) {
                const std::size_t row = volume_.linearIndex(box.lo.x, j, k);
                for (std::size_t i = row; i < row + std::size_t(box.hi.x - box.lo.x); ++i) {
                    lo = std::min(lo, voxels[i]);
                    hi = std::max(hi, voxels[i]);
                }
            }
        }
        const double range = double(hi) - double(lo);
        double scale =
            std::is_floating_point_v<T> ? (range > 0.0 ? kFloatLevels / range : 0.0) : 1.0;
        const double levels = std::floor(kMaxBuckets / double(segments)) - 1.0;
        if (range * scale > levels) {
            scale = levels / range;
        }
        maxStep_ = std::uint32_t(std::lround(range * scale));
        // Integers kept as they are take the exact path: the intensity minus the minimum.
        const bool exact = !std::is_floating_point_v<T> && scale == 1.0;
        Cell* const cells = cells_.data();
        forEachCell(bricks_, box, volume_, [&](std::size_t cell, std::ptrdiff_t voxel) {
            if (voxel >= 0) {
                const T v = voxels[std::size_t(voxel)];
                const std::uint16_t value =
                    exact ? std::uint16_t(int(v) - int(lo))
                          : std::uint16_t(std::lround((double(v) - double(lo)) * scale));
                cells[cell] = {kUnreached, value, kNoLabel};
            }
        });
    });
}

std::size_t SeedGrower::propagate(std::span<const SegmentMask> seeds) {
    // Dial's bucket queue over the key: a step adds at most maxStep_ * segments to it, so a
    // ring of a power of two buckets above (maxStep_ + 1) * segments holds every key still
    // queued. Stale entries (a voxel reached again nearer) are skipped.
    const std::uint32_t nl = std::uint32_t(segments_);
    const std::size_t ring = std::bit_ceil(std::size_t(maxStep_ + 1) * segments_);
    const std::size_t wrap = ring - 1;
    std::vector<std::vector<std::uint32_t>> buckets(ring);
    std::size_t queued = 0;
    for (std::size_t s = 0; s < seeds.size(); ++s) {
        seeds[s].forEachSet([&](std::size_t i) {
            const std::size_t p = padded(seeds[s].voxelOf(i));
            if (s < cells_[p].key) {
                if (cells_[p].label != s) {
                    relabelled_.push_back(std::uint32_t(p));
                }
                cells_[p] = {std::uint32_t(s), cells_[p].value, std::uint8_t(s)};
                buckets[s].push_back(std::uint32_t(p));
                ++queued;
            }
        });
    }
    // Steps to the six neighbours within a brick, and across to the next brick's cell.
    const std::size_t rowOfBricks = std::size_t(bricks_.x) * 512;
    const std::size_t sliceOfBricks = rowOfBricks * std::size_t(bricks_.y);
    const auto neighbours = [&](std::size_t p, std::size_t(&out)[6]) {
        const std::size_t x = p & 7, y = (p >> 3) & 7, z = (p >> 6) & 7;
        out[0] = x < 7 ? p + 1 : p + 512 - 7;
        out[1] = x > 0 ? p - 1 : p - 512 + 7;
        out[2] = y < 7 ? p + 8 : p + rowOfBricks - 56;
        out[3] = y > 0 ? p - 8 : p - rowOfBricks + 56;
        out[4] = z < 7 ? p + 64 : p + sliceOfBricks - 448;
        out[5] = z > 0 ? p - 64 : p - sliceOfBricks + 448;
    };
    Cell* const cells = cells_.data();
    std::size_t settled = 0;
    for (std::uint64_t current = 0; queued > 0; ++current) {
        std::vector<std::uint32_t>& bucket = buckets[current & wrap];
        // Entries pushed at the current key (a zero step) join this same bucket.
        for (std::size_t n = 0; n < bucket.size(); ++n) {
            const std::size_t p = bucket[n];
            // The visits jump round the box: ask for a later entry's cell and the lines of
            // its neighbours now (measured: about a third off the whole CT's first result).
            if (n + kPrefetchAhead < bucket.size()) {
                const Cell* ahead = cells + bucket[n + kPrefetchAhead];
                for (const std::ptrdiff_t line : {0, 8, -8, 64, -64}) {
                    __builtin_prefetch(ahead + line);
                }
            }
            --queued;
            const Cell here = cells[p];
            if (here.key != current) {
                continue;
            }
            ++settled;
            std::size_t around[6];
            neighbours(p, around);
            for (const std::size_t q : around) {
                const std::uint32_t step =
                    std::uint32_t(std::abs(int(here.value) - cells[q].value));
                // Saturates past 2^32 / segments (never reached with 16-bit intensities on
                // paths of under 65536 / segments voxels at full contrast each step).
                const std::uint64_t wide = std::uint64_t(here.key) + std::uint64_t(step) * nl;
                const std::uint32_t key =
                    std::uint32_t(std::min<std::uint64_t>(wide, kUnreached - 1));
                if (key < cells[q].key) {
                    if (cells[q].label != here.label) {
                        relabelled_.push_back(std::uint32_t(q));
                        cells[q].label = here.label;
                    }
                    cells[q].key = key;
                    buckets[key & wrap].push_back(std::uint32_t(q));
                    ++queued;
                }
            }
        }
        bucket.clear();
    }
    return settled;
}

GrowOutcome SeedGrower::grow(std::span<const SegmentMask> seeds) {
    const auto start = std::chrono::steady_clock::now();
    if (seeds.size() < 2 || seeds.size() > kMaxSegments) {
        throw std::invalid_argument("grow from seeds needs 2 to " + std::to_string(kMaxSegments) +
                                    " segments with seeds, not " + std::to_string(seeds.size()));
    }
    for (const SegmentMask& s : seeds) {
        if (s.dims() != volume_.dims()) {
            throw std::invalid_argument("grow from seeds: a seed mask lies on another grid");
        }
    }
    const VoxelBox bounds = seedBounds(seeds);
    if (bounds.voxelCount() == 0) {
        throw std::invalid_argument("grow from seeds: no seed voxel painted");
    }
    GrowOutcome out;
    out.incremental = canUpdate(seeds, bounds);
    if (!out.incremental) {
        VoxelBox box{glm::ivec3(0), volume_.dims()};
        if (options_.roiMarginMm > 0.0) {
            const glm::ivec3 pad(glm::ceil(options_.roiMarginMm / volume_.geometry().spacing));
            box = {glm::max(bounds.lo - pad, glm::ivec3(0)),
                   glm::min(bounds.hi + pad, volume_.dims())};
        }
        prepare(box, seeds.size());
    }
    relabelled_.clear();
    out.voxelsSettled = propagate(seeds);
    seeds_.assign(seeds.begin(), seeds.end());
    if (!out.incremental) {
        rebuildMasks();
    } else {
        for (const std::uint32_t cell : relabelled_) {
            const glm::ivec3 v = voxelOfCell(cell);
            const std::size_t at = volume_.linearIndex(v.x, v.y, v.z);
            for (std::size_t s = 0; s < masks_.size(); ++s) {
                masks_[s].set(at, s == cells_[cell].label);
            }
        }
    }
    relabelled_ = {};
    out.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

glm::ivec3 SeedGrower::voxelOfCell(std::size_t cell) const {
    const std::size_t brick = cell >> 9;
    const std::size_t bx = brick % std::size_t(bricks_.x);
    const std::size_t by = brick / std::size_t(bricks_.x) % std::size_t(bricks_.y);
    const std::size_t bz = brick / (std::size_t(bricks_.x) * std::size_t(bricks_.y));
    const glm::ivec3 g(int(bx * 8 + (cell & 7)), int(by * 8 + ((cell >> 3) & 7)),
                       int(bz * 8 + ((cell >> 6) & 7)));
    return g - 1 + box_.lo;
}

void SeedGrower::rebuildMasks() {
    masks_.assign(segments_, SegmentMask(volume_.dims()));
    forEachCell(bricks_, box_, volume_, [&](std::size_t cell, std::ptrdiff_t voxel) {
        if (voxel >= 0 && cells_[cell].label != kNoLabel) {
            masks_[cells_[cell].label].set(std::size_t(voxel));
        }
    });
}

std::vector<SegmentMask> growFromSeeds(const Volume& volume, std::span<const SegmentMask> seeds,
                                       const GrowOptions& options) {
    SeedGrower grower(volume, options);
    grower.grow(seeds);
    return std::vector<SegmentMask>(grower.masks());
}

} // namespace lucent
