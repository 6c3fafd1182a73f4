#include "core/volume/BrickGrid.h"

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace lucent {

namespace {

// One axis cut into segments at every padded-brick boundary: each voxel
// coordinate lies in exactly one segment, and every padded brick range is a
// run of whole segments. Min/max per 3-D cell of segments, in one pass over
// the voxels, then give every brick's min/max exactly, whatever the overlap.
struct AxisSegments {
    std::vector<int> bounds;                  // ascending, from 0 to dim
    std::vector<int> segmentOf;               // per voxel coordinate
    std::vector<std::pair<int, int>> ofBrick; // per brick: first and last segment (inclusive)

    int count() const { return static_cast<int>(bounds.size()) - 1; }
};

std::pair<int, int> paddedRange(int brick, int size, int overlap, int dim) {
    const auto first = static_cast<std::int64_t>(brick) * size;
    const auto last = std::min<std::int64_t>(first + size, dim);
    return {static_cast<int>(std::max<std::int64_t>(first - overlap, 0)),
            static_cast<int>(std::min<std::int64_t>(last + overlap, dim))};
}

AxisSegments segmentAxis(int dim, int bricks, int size, int overlap) {
    AxisSegments a;
    a.bounds = {0, dim};
    for (int b = 0; b < bricks; ++b) {
        const auto [lo, hi] = paddedRange(b, size, overlap, dim);
        a.bounds.push_back(lo);
        a.bounds.push_back(hi);
    }
    std::sort(a.bounds.begin(), a.bounds.end());
    a.bounds.erase(std::unique(a.bounds.begin(), a.bounds.end()), a.bounds.end());
    a.segmentOf.resize(static_cast<std::size_t>(dim));
    for (int s = 0; s < a.count(); ++s) {
        std::fill(a.segmentOf.begin() + a.bounds[static_cast<std::size_t>(s)],
                  a.segmentOf.begin() + a.bounds[static_cast<std::size_t>(s) + 1], s);
    }
    for (int b = 0; b < bricks; ++b) {
        const auto [lo, hi] = paddedRange(b, size, overlap, dim);
        a.ofBrick.emplace_back(a.segmentOf[static_cast<std::size_t>(lo)],
                               a.segmentOf[static_cast<std::size_t>(hi) - 1]);
    }
    return a;
}

constexpr float kInf = std::numeric_limits<float>::infinity();

struct CellRange {
    std::vector<float> lo;
    std::vector<float> hi;
    explicit CellRange(std::size_t n) : lo(n, kInf), hi(n, -kInf) {}
};

// Folds one row of voxels into the cells (one per x segment) starting at
// lo/hi. Compares in the voxel type (vectorises); NaN never compares less or
// greater, so it is skipped.
template <class T> void scanRow(const T* row, const AxisSegments& xs, float* lo, float* hi) {
    constexpr T kLowest = std::is_floating_point_v<T> ? -std::numeric_limits<T>::infinity()
                                                      : std::numeric_limits<T>::lowest();
    constexpr T kHighest = std::is_floating_point_v<T> ? std::numeric_limits<T>::infinity()
                                                       : std::numeric_limits<T>::max();
    for (std::size_t s = 0; s + 1 < xs.bounds.size(); ++s) {
        T mn = kHighest;
        T mx = kLowest;
        for (int i = xs.bounds[s]; i < xs.bounds[s + 1]; ++i) {
            const T v = row[i];
            mn = v < mn ? v : mn;
            mx = v > mx ? v : mx;
        }
        lo[s] = std::min(lo[s], static_cast<float>(mn));
        hi[s] = std::max(hi[s], static_cast<float>(mx));
    }
}

// Per-thread copies of the cells cost threads * cells floats; beyond this
// the pass splits the work by (z segment, y segment) instead.
constexpr std::size_t kMaxCopiedCells = std::size_t(1) << 22;

template <class T>
CellRange cellRanges(const T* voxels, glm::ivec3 dims, const AxisSegments& xs,
                     const AxisSegments& ys, const AxisSegments& zs) {
    const std::size_t nx = static_cast<std::size_t>(xs.count());
    const std::size_t ny = static_cast<std::size_t>(ys.count());
    const std::size_t cells = nx * ny * static_cast<std::size_t>(zs.count());
    const auto rowAt = [&](int j, int k) {
        return voxels + static_cast<std::size_t>(dims.x) *
                            (static_cast<std::size_t>(j) +
                             static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(k));
    };
    const auto cellBase = [&](int j, int k) {
        return nx * (static_cast<std::size_t>(ys.segmentOf[static_cast<std::size_t>(j)]) +
                     ny * static_cast<std::size_t>(zs.segmentOf[static_cast<std::size_t>(k)]));
    };
    const int threads = std::max(1, omp_get_max_threads());
    const int pairs = ys.count() * zs.count();
    CellRange out(cells);
    if (pairs >= 4 * threads || cells * static_cast<std::size_t>(threads) > kMaxCopiedCells) {
        // Each (y segment, z segment) pair owns its own cells: no sharing.
#pragma omp parallel for schedule(dynamic)
        for (int p = 0; p < pairs; ++p) {
            const std::size_t ySeg = static_cast<std::size_t>(p % ys.count());
            const std::size_t zSeg = static_cast<std::size_t>(p / ys.count());
            for (int k = zs.bounds[zSeg]; k < zs.bounds[zSeg + 1]; ++k) {
                for (int j = ys.bounds[ySeg]; j < ys.bounds[ySeg + 1]; ++j) {
                    const std::size_t base = cellBase(j, k);
                    scanRow(rowAt(j, k), xs, out.lo.data() + base, out.hi.data() + base);
                }
            }
        }
        return out;
    }
    // Few cells: every thread folds its rows into its own copy, merged after.
    std::vector<CellRange> copies(static_cast<std::size_t>(threads), CellRange(cells));
    const std::int64_t rows = static_cast<std::int64_t>(dims.y) * dims.z;
#pragma omp parallel num_threads(threads)
    {
        CellRange& mine = copies[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
        for (std::int64_t r = 0; r < rows; ++r) {
            const int j = static_cast<int>(r % dims.y);
            const int k = static_cast<int>(r / dims.y);
            const std::size_t base = cellBase(j, k);
            scanRow(rowAt(j, k), xs, mine.lo.data() + base, mine.hi.data() + base);
        }
    }
    for (const CellRange& c : copies) {
        for (std::size_t i = 0; i < cells; ++i) {
            out.lo[i] = std::min(out.lo[i], c.lo[i]);
            out.hi[i] = std::max(out.hi[i], c.hi[i]);
        }
    }
    return out;
}

int bricksAlong(int dim, int size) {
    return static_cast<int>((static_cast<std::int64_t>(dim) + size - 1) / size);
}

} // namespace

BrickGrid::BrickGrid(const Volume& volume, int brickSize, int overlap)
    : brickSize_(brickSize), overlap_(overlap) {
    if (brickSize < 1) {
        throw std::invalid_argument("brick size must be at least 1, not " +
                                    std::to_string(brickSize));
    }
    if (overlap < 0) {
        throw std::invalid_argument("brick overlap must not be negative, not " +
                                    std::to_string(overlap));
    }
    if (volume.empty()) {
        return;
    }
    dims_ = volume.dims();
    perAxis_ = {bricksAlong(dims_.x, brickSize), bricksAlong(dims_.y, brickSize),
                bricksAlong(dims_.z, brickSize)};
    const AxisSegments xs = segmentAxis(dims_.x, perAxis_.x, brickSize, overlap);
    const AxisSegments ys = segmentAxis(dims_.y, perAxis_.y, brickSize, overlap);
    const AxisSegments zs = segmentAxis(dims_.z, perAxis_.z, brickSize, overlap);
    const CellRange cells = visitVoxels(
        volume, [&](auto voxels) { return cellRanges(voxels.data(), dims_, xs, ys, zs); });

    bricks_.resize(static_cast<std::size_t>(perAxis_.x) * static_cast<std::size_t>(perAxis_.y) *
                   static_cast<std::size_t>(perAxis_.z));
    const auto nx = static_cast<std::size_t>(xs.count());
    const auto ny = static_cast<std::size_t>(ys.count());
    const auto n = static_cast<std::int64_t>(bricks_.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t id = 0; id < n; ++id) {
        Brick& b = bricks_[static_cast<std::size_t>(id)];
        b.index = {static_cast<int>(id % perAxis_.x),
                   static_cast<int>((id / perAxis_.x) % perAxis_.y),
                   static_cast<int>(id / (static_cast<std::int64_t>(perAxis_.x) * perAxis_.y))};
        b.first = b.index * brickSize;
        b.last = glm::min(b.first + brickSize, dims_);
        float lo = kInf;
        float hi = -kInf;
        const auto [x0, x1] = xs.ofBrick[static_cast<std::size_t>(b.index.x)];
        const auto [y0, y1] = ys.ofBrick[static_cast<std::size_t>(b.index.y)];
        const auto [z0, z1] = zs.ofBrick[static_cast<std::size_t>(b.index.z)];
        for (int z = z0; z <= z1; ++z) {
            for (int y = y0; y <= y1; ++y) {
                for (int x = x0; x <= x1; ++x) {
                    const std::size_t c =
                        static_cast<std::size_t>(x) +
                        nx * (static_cast<std::size_t>(y) + ny * static_cast<std::size_t>(z));
                    lo = std::min(lo, cells.lo[c]);
                    hi = std::max(hi, cells.hi[c]);
                }
            }
        }
        b.minValue = lo;
        b.maxValue = hi;
    }
}

std::uint32_t BrickGrid::idOf(glm::ivec3 index) const {
    if (glm::any(glm::lessThan(index, glm::ivec3(0))) ||
        glm::any(glm::greaterThanEqual(index, perAxis_))) {
        throw std::out_of_range("brick index (" + std::to_string(index.x) + ", " +
                                std::to_string(index.y) + ", " + std::to_string(index.z) +
                                ") outside a grid of " + std::to_string(perAxis_.x) + "x" +
                                std::to_string(perAxis_.y) + "x" + std::to_string(perAxis_.z));
    }
    return static_cast<std::uint32_t>(
        index.x + perAxis_.x * (static_cast<std::int64_t>(index.y) +
                                static_cast<std::int64_t>(perAxis_.y) * index.z));
}

const Brick& BrickGrid::brickAt(glm::ivec3 index) const {
    return bricks_[idOf(index)];
}

glm::ivec3 BrickGrid::paddedFirst(const Brick& brick) const {
    return glm::max(brick.first - overlap_, glm::ivec3(0));
}

glm::ivec3 BrickGrid::paddedLast(const Brick& brick) const {
    glm::ivec3 r;
    for (int a = 0; a < 3; ++a) {
        r[a] = static_cast<int>(
            std::min<std::int64_t>(static_cast<std::int64_t>(brick.last[a]) + overlap_, dims_[a]));
    }
    return r;
}

std::vector<std::uint32_t> visibleBricks(const BrickGrid& grid,
                                         const std::function<bool(double lo, double hi)>& isVisible,
                                         const ClipBox& clip) {
    std::vector<std::uint32_t> ids;
    const std::vector<Brick>& bricks = grid.bricks();
    for (std::size_t id = 0; id < bricks.size(); ++id) {
        const Brick& b = bricks[id];
        const glm::dvec3 lo(grid.paddedFirst(b));
        const glm::dvec3 hi(grid.paddedLast(b) - 1);
        const bool meets = glm::all(glm::lessThanEqual(clip.lo, hi)) &&
                           glm::all(glm::greaterThanEqual(clip.hi, lo));
        if (meets && isVisible(b.minValue, b.maxValue)) {
            ids.push_back(static_cast<std::uint32_t>(id));
        }
    }
    return ids;
}

} // namespace lucent
