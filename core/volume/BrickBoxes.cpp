#include "core/volume/BrickBoxes.h"

#include <algorithm>
#include <cmath>

#include "core/volume/LodPyramid.h"

namespace lucent {

namespace {

glm::ivec3 ceilDiv(glm::ivec3 a, int b) {
    return (a + b - 1) / b;
}

std::size_t countOf(glm::ivec3 per) {
    return std::size_t(per.x) * std::size_t(per.y) * std::size_t(per.z);
}

std::size_t idOf(glm::ivec3 i, glm::ivec3 per) {
    return std::size_t(i.x) + std::size_t(per.x) * (std::size_t(i.y) + std::size_t(per.y) * i.z);
}

} // namespace

FilterReach filterReach(bool cubic, bool differencesInShader) {
    // What the filter reads, and a guard texel on each side: a GPU's texture
    // coordinate at a texel centre may round across it and weigh the next
    // texel by a 256th or less; in the atlas that texel belongs to another
    // box (measured: an isosurface crossing flips on axis-aligned rays).
    return cubic || differencesInShader ? FilterReach{2, 3} : FilterReach{1, 2};
}

StoredBox storedBox(const SampleBox& box, int level, FilterReach reach) {
    // Samples p in [lo, hi): level positions in [lo', hi'), floors up to ceil(hi') - 1.
    const glm::dvec3 lo = LodPyramid::fromLevel0(glm::dvec3(box.lo), level);
    const glm::dvec3 hi = LodPyramid::fromLevel0(glm::dvec3(box.hi), level);
    StoredBox s;
    s.lo = glm::ivec3(glm::floor(lo)) - reach.below;
    const glm::ivec3 last = glm::ivec3(glm::ceil(hi)) - 1 + reach.above;
    s.size = glm::max(last - s.lo + 1, glm::ivec3(1));
    return s;
}

BrickBoxes::BrickBoxes(glm::ivec3 dims, int brickSize, int cellSize)
    : dims_(dims), brickSize_(brickSize), cellSize_(cellSize), cellsPer_(ceilDiv(dims, cellSize)),
      bricksPer_(ceilDiv(dims, brickSize)) {}

std::size_t BrickBoxes::cellCount() const {
    return countOf(cellsPer_);
}

std::size_t BrickBoxes::brickCount() const {
    return countOf(bricksPer_);
}

glm::ivec3 BrickBoxes::brickIndex(std::size_t id) const {
    const std::size_t x = std::size_t(bricksPer_.x), y = std::size_t(bricksPer_.y);
    return {int(id % x), int((id / x) % y), int(id / (x * y))};
}

std::uint32_t BrickBoxes::brickOfCell(glm::ivec3 cell) const {
    return std::uint32_t(idOf(glm::min(cell * cellSize_ / brickSize_, bricksPer_ - 1), bricksPer_));
}

std::uint32_t BrickBoxes::brickOfLastVoxel(glm::ivec3 cell) const {
    const glm::ivec3 last = glm::min(cell * cellSize_ + cellSize_, dims_) - 1;
    return std::uint32_t(idOf(glm::min(last / brickSize_, bricksPer_ - 1), bricksPer_));
}

std::vector<std::uint32_t> BrickBoxes::levelCellOf(const BrickGrid& levelCells, int level) const {
    std::vector<std::uint32_t> out(cellCount(), 0);
    const glm::ivec3 per = levelCells.bricksPerAxis();
    const int size = levelCells.brickSize();
    for (int z = 0; z < cellsPer_.z; ++z) {
        for (int y = 0; y < cellsPer_.y; ++y) {
            for (int x = 0; x < cellsPer_.x; ++x) {
                const glm::ivec3 c(x, y, z);
                const glm::dvec3 lo(c * cellSize_);
                const glm::dvec3 hi = glm::min(lo + double(cellSize_), glm::dvec3(dims_));
                const glm::dvec3 centre = LodPyramid::fromLevel0(0.5 * (lo + hi - 1.0), level);
                const glm::ivec3 at =
                    glm::clamp(glm::ivec3(glm::floor(centre)) / size, glm::ivec3(0), per - 1);
                out[idOf(c, cellsPer_)] = levelCells.idOf(at);
            }
        }
    }
    return out;
}

std::vector<std::uint8_t>
BrickBoxes::visibleCells(const BrickGrid& levelCells, int level,
                         const std::function<bool(double, double)>& visible,
                         const ClipBox& clip) const {
    const std::vector<std::uint32_t> at = levelCellOf(levelCells, level);
    std::vector<std::uint8_t> out(cellCount(), 0);
#pragma omp parallel for schedule(static)
    for (int z = 0; z < cellsPer_.z; ++z) {
        for (int y = 0; y < cellsPer_.y; ++y) {
            for (int x = 0; x < cellsPer_.x; ++x) {
                const glm::ivec3 c(x, y, z);
                // Samples lie in [lo, hi) of the cell; the clip box is closed.
                const glm::dvec3 lo(c * cellSize_), hi = lo + double(cellSize_);
                if (glm::any(glm::greaterThan(lo, clip.hi)) ||
                    glm::any(glm::lessThan(hi, clip.lo))) {
                    continue;
                }
                const std::size_t id = idOf(c, cellsPer_);
                const Brick& b = levelCells.bricks()[at[id]];
                out[id] = visible(b.minValue, b.maxValue) ? 1 : 0;
            }
        }
    }
    return out;
}

std::vector<std::optional<SampleBox>> BrickBoxes::boxes(const std::vector<std::uint8_t>& cells,
                                                        bool withNeighbours) const {
    // 2: visible, 1: next to a visible cell (withNeighbours).
    std::vector<std::uint8_t> mark(cells.size(), 0);
    for (int z = 0; z < cellsPer_.z; ++z) {
        for (int y = 0; y < cellsPer_.y; ++y) {
            for (int x = 0; x < cellsPer_.x; ++x) {
                const glm::ivec3 c(x, y, z);
                if (cells[idOf(c, cellsPer_)] == 0) {
                    continue;
                }
                mark[idOf(c, cellsPer_)] = 2;
                if (!withNeighbours) {
                    continue;
                }
                const glm::ivec3 lo = glm::max(c - 1, glm::ivec3(0));
                const glm::ivec3 hi = glm::min(c + 1, cellsPer_ - 1);
                for (int k = lo.z; k <= hi.z; ++k) {
                    for (int j = lo.y; j <= hi.y; ++j) {
                        for (int i = lo.x; i <= hi.x; ++i) {
                            std::uint8_t& m = mark[idOf({i, j, k}, cellsPer_)];
                            m = std::max<std::uint8_t>(m, 1);
                        }
                    }
                }
            }
        }
    }
    std::vector<std::optional<SampleBox>> out(brickCount());
    for (int z = 0; z < cellsPer_.z; ++z) {
        for (int y = 0; y < cellsPer_.y; ++y) {
            for (int x = 0; x < cellsPer_.x; ++x) {
                const glm::ivec3 c(x, y, z);
                const std::uint8_t m = mark[idOf(c, cellsPer_)];
                if (m == 0) {
                    continue;
                }
                const glm::ivec3 cellLo = c * cellSize_;
                const glm::ivec3 cellHi = glm::min(cellLo + cellSize_, dims_);
                // A cell may straddle bricks where the brick size is no multiple of the cell's.
                const glm::ivec3 bLo = cellLo / brickSize_;
                const glm::ivec3 bHi = glm::min((cellHi - 1) / brickSize_, bricksPer_ - 1);
                for (int k = bLo.z; k <= bHi.z; ++k) {
                    for (int j = bLo.y; j <= bHi.y; ++j) {
                        for (int i = bLo.x; i <= bHi.x; ++i) {
                            const glm::ivec3 b(i, j, k);
                            const glm::ivec3 lo = glm::max(cellLo, b * brickSize_);
                            const glm::ivec3 hi = glm::min(cellHi, (b + 1) * brickSize_);
                            auto& box = out[idOf(b, bricksPer_)];
                            if (!box) {
                                box = SampleBox{lo, hi, m == 2};
                            } else {
                                box->lo = glm::min(box->lo, lo);
                                box->hi = glm::max(box->hi, hi);
                                box->contributes = box->contributes || m == 2;
                            }
                        }
                    }
                }
            }
        }
    }
    return out;
}

} // namespace lucent
