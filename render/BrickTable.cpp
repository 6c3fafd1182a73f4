#include "render/BrickTable.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lucent {

std::size_t BrickTable::bytes() const {
    return entries.size() * sizeof(glm::uvec4) + codes.size() + ranges.size() * sizeof(glm::vec2);
}

glm::uvec4 pageEntry(glm::ivec4 page, const SampleBox& box, glm::ivec3 brickFirst) {
    const glm::ivec3 slot(page);
    const glm::ivec3 lo = box.lo - brickFirst, hi = box.hi - brickFirst;
    if (glm::any(glm::lessThan(slot, glm::ivec3(-32768))) ||
        glm::any(glm::greaterThan(slot, glm::ivec3(32767)))) {
        throw std::invalid_argument("page entry: an atlas slot beyond 16 bits");
    }
    if (glm::any(glm::lessThan(glm::min(lo, hi), glm::ivec3(0))) ||
        glm::any(glm::greaterThan(glm::max(lo, hi), glm::ivec3(kMaxPageBrickSize)))) {
        throw std::invalid_argument("page entry: a sample box beyond " +
                                    std::to_string(kMaxPageBrickSize) + " voxels of its brick");
    }
    const glm::uvec3 s = glm::uvec3(slot) & 0xffffu;
    const auto tenBits = [](glm::ivec3 v) {
        return std::uint32_t(v.x) | std::uint32_t(v.y) << 10 | std::uint32_t(v.z) << 20;
    };
    return {s.x | s.y << 16, s.z | std::uint32_t(page.w) << 16, tenBits(lo), tenBits(hi)};
}

BrickTable makeBrickTable(const BrickBoxes& boxes, const std::vector<ShownBrick>& shown,
                          const std::vector<CellRanges>& levels,
                          const std::function<bool(double, double)>& visible, bool decides,
                          bool cubic) {
    BrickTable t;
    t.brickSize = boxes.brickSize();
    t.bricksPerAxis = boxes.bricksPerAxis();
    t.cellsPerAxis = boxes.cellsPerAxis();
    t.page.assign(shown.size(), glm::ivec4(0));
    t.entries.assign(shown.size(), glm::uvec4(0));
    t.perLevel.assign(levels.size(), 0);
    std::vector<int> levelOf(shown.size(), -1);
    for (std::size_t b = 0; b < shown.size(); ++b) {
        const ShownBrick& s = shown[b];
        if (!s.entry) {
            continue;
        }
        const int state = s.box.contributes ? 1 : 2;
        t.page[b] = glm::ivec4(s.entry->at - s.entry->box.lo, state | (s.entry->level << 2));
        t.entries[b] = pageEntry(t.page[b], s.box, boxes.brickIndex(b) * t.brickSize);
        levelOf[b] = s.entry->level;
        ++t.perLevel[std::size_t(s.entry->level)];
    }
    const glm::ivec3 per = t.cellsPerAxis;
    const std::size_t cellCount = boxes.cellCount();
    t.codes.assign(cellCount, 0);
    t.ranges.assign(cellCount, glm::vec2(0.0f));
    // A cell in two bricks (a brick size that is no multiple of the cell's) is
    // never leapt, and its range is that of every level in use.
    const auto rangeAt = [&](std::size_t cell, int level) {
        const CellRanges& l = levels[std::size_t(level)];
        const Brick& c = l.cells->bricks()[(*l.at)[cell]];
        return glm::dvec2(c.minValue, c.maxValue);
    };
#pragma omp parallel for schedule(static)
    for (int z = 0; z < per.z; ++z) {
        for (int y = 0; y < per.y; ++y) {
            for (int x = 0; x < per.x; ++x) {
                const glm::ivec3 c(x, y, z);
                const std::size_t id =
                    std::size_t(x) + std::size_t(per.x) * (std::size_t(y) + std::size_t(per.y) * z);
                const std::uint32_t brick = boxes.brickOfCell(c);
                const bool inOne = boxes.brickOfCell(c) == boxes.brickOfLastVoxel(c);
                glm::dvec2 r(0.0);
                if (inOne) {
                    const int level = std::max(levelOf[brick], 0);
                    r = rangeAt(id, level);
                    const int state = t.page[brick].w & 3;
                    if (state == 0 || (decides && state == 2)) {
                        t.codes[id] = 2;
                    } else if (decides && !visible(r.x, r.y)) {
                        t.codes[id] = 1;
                    }
                } else {
                    r = glm::dvec2(1e300, -1e300);
                    for (int l = 0; l < int(levels.size()); ++l) {
                        if (t.perLevel[std::size_t(l)] > 0 || l == 0) {
                            const glm::dvec2 q = rangeAt(id, l);
                            r = glm::dvec2(std::min(r.x, q.x), std::max(r.y, q.y));
                        }
                    }
                }
                const double margin = cubic ? 1e-5 * (std::abs(r.x) + std::abs(r.y) + 1.0) : 0.0;
                t.ranges[id] = glm::vec2(float(r.x - margin), float(r.y + margin));
            }
        }
    }
    return t;
}

} // namespace lucent
