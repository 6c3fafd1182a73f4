#include "core/surface/TriangleGrid.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace lucent {

namespace {

constexpr int kMaxCellsPerAxis = 1 << 21; // Morton keys hold 21 bits per axis

// Spreads the low 21 bits of v to every third bit.
std::uint64_t spreadBits(std::uint64_t v) {
    v &= 0x1fffffu;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

glm::ivec3 cellCounts(const glm::dvec3& extent, double cell) {
    const glm::dvec3 n = glm::floor(extent / cell) + 1.0;
    return glm::ivec3(glm::min(n, glm::dvec3(kMaxCellsPerAxis)));
}

double product(const glm::ivec3& d) {
    return double(d.x) * d.y * d.z;
}

} // namespace

GridFrame::GridFrame(const glm::dvec3& lo, const glm::dvec3& hi, double cellSize,
                     std::size_t maxCells)
    : origin_(lo) {
    const glm::dvec3 extent = glm::max(hi - lo, glm::dvec3(0.0));
    const double cap = double(std::max<std::size_t>(maxCells, 4096));
    double cell = cellSize;
    if (!(cell > 0.0) || !std::isfinite(cell)) {
        throw std::invalid_argument("grid cell size must be finite and > 0");
    }
    // Coarsen in steps of 2^(1/3) until the grid is small enough.
    while (
        product(cellCounts(extent, cell)) > cap ||
        glm::any(glm::greaterThanEqual(cellCounts(extent, cell), glm::ivec3(kMaxCellsPerAxis)))) {
        cell *= 1.2599210498948732;
    }
    cell_ = cell;
    invCell_ = 1.0 / cell;
    dims_ = cellCounts(extent, cell);
}

std::uint64_t GridFrame::mortonKey(const glm::dvec3& p) const {
    const glm::ivec3 c = cellOf(p);
    return spreadBits(std::uint64_t(c.x)) | spreadBits(std::uint64_t(c.y)) << 1 |
           spreadBits(std::uint64_t(c.z)) << 2;
}

void QueryStamps::beginQuery() {
    if (++current_ == 0) { // wrapped after 2³² queries: old stamps could match again
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        current_ = 1;
    }
}

TriangleGrid::TriangleGrid(const GridFrame& frame, std::span<const PreparedTriangle> triangles)
    : frame_(frame), cellStart_(frame.cellCount() + 1, 0u) {
    if (triangles.size() >= std::numeric_limits<std::uint32_t>::max()) {
        throw std::invalid_argument("too many triangles for the grid's 32-bit ids");
    }
    auto forEachCell = [&](const PreparedTriangle& t, auto&& f) {
        const glm::ivec3 lo = frame_.cellOf(glm::dvec3(t.boxLo)),
                         hi = frame_.cellOf(glm::dvec3(t.boxHi));
        for (int z = lo.z; z <= hi.z; ++z) {
            for (int y = lo.y; y <= hi.y; ++y) {
                for (int x = lo.x; x <= hi.x; ++x) {
                    f(frame_.linear({x, y, z}));
                }
            }
        }
    };
    std::size_t total = 0;
    for (const PreparedTriangle& t : triangles) {
        forEachCell(t, [&](std::size_t c) { ++cellStart_[c + 1], ++total; });
    }
    if (total >= std::numeric_limits<std::uint32_t>::max()) {
        throw std::invalid_argument("too many grid entries for 32-bit offsets");
    }
    for (std::size_t c = 1; c < cellStart_.size(); ++c) {
        cellStart_[c] += cellStart_[c - 1];
    }
    entries_.resize(total);
    std::vector<std::uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
    for (std::uint32_t id = 0; id < triangles.size(); ++id) {
        forEachCell(triangles[id], [&](std::size_t c) { entries_[fill[c]++] = id; });
    }
}

} // namespace lucent
