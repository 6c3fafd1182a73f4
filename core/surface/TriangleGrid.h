#pragma once
// A uniform grid over triangle boxes for ball queries: each triangle is listed
// in every cell its box overlaps (CSR arrays, built in O(n) by counting), and a
// query visits the cells that reach within R of the centre, each triangle once
// thanks to a per-thread stamp array.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/surface/SphereIntegrals.h"

namespace lucent {

// Placement of the cells: an origin, a cubic cell size and the cell counts.
class GridFrame {
public:
    // Cells of `cellSize` over the box lo .. hi, made coarser where more than
    // `maxCells` cells (at least 4096) would be needed.
    GridFrame(const glm::dvec3& lo, const glm::dvec3& hi, double cellSize, std::size_t maxCells);

    double cellSize() const { return cell_; }
    glm::ivec3 dims() const { return dims_; }
    std::size_t cellCount() const { return std::size_t(dims_.x) * dims_.y * dims_.z; }

    // The cell holding p, clamped to the grid.
    glm::ivec3 cellOf(const glm::dvec3& p) const {
        const glm::dvec3 c = glm::floor((p - origin_) * invCell_);
        return glm::clamp(glm::ivec3(glm::clamp(c, glm::dvec3(-1.0), glm::dvec3(dims_))),
                          glm::ivec3(0), dims_ - 1);
    }
    std::size_t linear(const glm::ivec3& c) const {
        return std::size_t(c.x) +
               std::size_t(dims_.x) * (std::size_t(c.y) + std::size_t(dims_.y) * c.z);
    }
    // Z-order key of p's cell: sorting by it keeps neighbours in space near in memory.
    std::uint64_t mortonKey(const glm::dvec3& p) const;
    // Lower corner of cell c.
    glm::dvec3 corner(const glm::ivec3& c) const { return origin_ + glm::dvec3(c) * cell_; }

private:
    glm::dvec3 origin_{0.0};
    double cell_ = 1.0, invCell_ = 1.0;
    glm::ivec3 dims_{1};
};

// Marks which triangles one query has seen; one per thread.
class QueryStamps {
public:
    explicit QueryStamps(std::size_t triangles) : stamp_(triangles, 0u) {}
    void beginQuery();
    bool firstVisit(std::uint32_t id) {
        if (stamp_[id] == current_) {
            return false;
        }
        stamp_[id] = current_;
        return true;
    }

private:
    std::vector<std::uint32_t> stamp_;
    std::uint32_t current_ = 0;
};

class TriangleGrid {
public:
    TriangleGrid(const GridFrame& frame, std::span<const PreparedTriangle> triangles);

    const GridFrame& frame() const { return frame_; }
    std::size_t entryCount() const { return entries_.size(); }
    std::size_t memoryBytes() const {
        return (cellStart_.size() + entries_.size()) * sizeof(std::uint32_t);
    }

    // Calls visit(id) once for each triangle listed in a cell within `radius`
    // of `centre`: a superset of the triangles that meet the ball.
    template <class Visit>
    void forEachCandidate(const glm::dvec3& centre, double radius, QueryStamps& stamps,
                          Visit&& visit) const {
        stamps.beginQuery();
        const glm::ivec3 lo = frame_.cellOf(centre - radius), hi = frame_.cellOf(centre + radius);
        const double cell = frame_.cellSize();
        // A hair wider than R: a point on a cell face may have been binned next door.
        const double reach = radius + 1e-9 * cell, r2 = reach * reach;
        const glm::dvec3 base = frame_.corner(lo) - centre;
        for (int z = lo.z; z <= hi.z; ++z) {
            const double dz2 = axisGap2(base.z + (z - lo.z) * cell, cell);
            for (int y = lo.y; y <= hi.y; ++y) {
                const double dyz2 = dz2 + axisGap2(base.y + (y - lo.y) * cell, cell);
                if (dyz2 > r2) {
                    continue;
                }
                for (int x = lo.x; x <= hi.x; ++x) {
                    if (dyz2 + axisGap2(base.x + (x - lo.x) * cell, cell) > r2) {
                        continue;
                    }
                    const std::size_t c = frame_.linear({x, y, z});
                    for (std::uint32_t e = cellStart_[c]; e < cellStart_[c + 1]; ++e) {
                        if (stamps.firstVisit(entries_[e])) {
                            visit(entries_[e]);
                        }
                    }
                }
            }
        }
    }

private:
    // Squared distance from 0 to the interval [start, start + width].
    static double axisGap2(double start, double width) {
        const double gap = start > 0.0 ? start : (start + width < 0.0 ? -(start + width) : 0.0);
        return gap * gap;
    }

    GridFrame frame_;
    std::vector<std::uint32_t> cellStart_; // CSR: entries of cell c are [start[c], start[c+1])
    std::vector<std::uint32_t> entries_;   // triangle ids
};

} // namespace lucent
