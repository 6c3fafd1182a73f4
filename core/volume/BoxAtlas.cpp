#include "core/volume/BoxAtlas.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lucent {

namespace {

std::size_t volumeOf(glm::ivec3 s) {
    return std::size_t(s.x) * std::size_t(s.y) * std::size_t(s.z);
}

} // namespace

BoxAtlas::BoxAtlas(glm::ivec3 extent) : extent_(extent) {
    if (glm::any(glm::lessThan(extent, glm::ivec3(1)))) {
        throw std::invalid_argument("a box atlas needs a positive extent");
    }
    free_.push_back({glm::ivec3(0), extent});
}

std::size_t BoxAtlas::texels() const {
    return volumeOf(extent_);
}

std::optional<glm::ivec3> BoxAtlas::place(glm::ivec3 size) {
    if (glm::any(glm::lessThan(size, glm::ivec3(1)))) {
        throw std::invalid_argument("a box to place needs a positive size");
    }
    std::size_t best = free_.size(), bestLeft = std::numeric_limits<std::size_t>::max();
    for (std::size_t n = 0; n < free_.size(); ++n) {
        const Free& f = free_[n];
        if (glm::all(glm::lessThanEqual(size, f.size))) {
            const std::size_t left = volumeOf(f.size) - volumeOf(size);
            if (left < bestLeft) {
                best = n;
                bestLeft = left;
            }
        }
    }
    if (best == free_.size()) {
        return std::nullopt;
    }
    const Free f = free_[best];
    free_.erase(free_.begin() + std::ptrdiff_t(best));
    // Cut the rest along the axes with the most left over first, so that the
    // largest free boxes stay whole: the first cut takes the full cross-section.
    glm::ivec3 order(0, 1, 2);
    const glm::ivec3 left = f.size - size;
    std::sort(&order[0], &order[0] + 3, [&](int a, int b) { return left[a] > left[b]; });
    glm::ivec3 kept = f.size; // the part of f still to cut, shrinking to the placed box
    for (int n = 0; n < 3; ++n) {
        const int a = order[n];
        if (left[a] == 0) {
            continue;
        }
        Free piece{f.origin, kept};
        piece.origin[a] += size[a];
        piece.size[a] = left[a];
        free_.push_back(piece);
        kept[a] = size[a];
    }
    used_ += volumeOf(size);
    return f.origin;
}

void BoxAtlas::release(glm::ivec3 origin, glm::ivec3 size) {
    free_.push_back({origin, size});
    used_ -= std::min(used_, volumeOf(size));
}

glm::ivec3 BoxAtlas::extentFor(std::size_t texels, glm::ivec3 largest, int maxSide,
                               std::size_t maxTexels) {
    if (glm::any(glm::greaterThan(largest, glm::ivec3(maxSide))) ||
        double(texels) > std::pow(double(maxSide), 3.0)) {
        throw std::length_error("boxes of " + std::to_string(texels) +
                                " texels do not fit a 3D texture of at most " +
                                std::to_string(maxSide) + " a side");
    }
    // A square of whole boxes in x and y, about the cube root of the texels
    // (so that the largest boxes tile it), and z as deep as the rest needs.
    const glm::ivec3 box = glm::max(largest, glm::ivec3(1));
    const int unit = std::max(box.x, box.y);
    int across = std::max(1, int(std::cbrt(double(texels)) / unit));
    glm::ivec3 e;
    for (;;) {
        e.x = std::min(maxSide, std::max(box.x, across * unit));
        e.y = std::min(maxSide, std::max(box.y, across * unit));
        const std::size_t layer = std::size_t(e.x) * std::size_t(e.y);
        e.z = int(std::max<std::size_t>(std::size_t(box.z), (texels + layer - 1) / layer));
        if (e.z <= maxSide || (e.x == maxSide && e.y == maxSide)) {
            break;
        }
        ++across;
    }
    e.z = std::min(e.z, maxSide);
    // Within maxTexels where the largest box still fits: the rounding up of
    // the sides must not take the atlas past a budget.
    while (volumeOf(e) > maxTexels) {
        const std::size_t layer = std::size_t(e.x) * std::size_t(e.y);
        if (maxTexels / layer >= std::size_t(box.z)) {
            e.z = int(maxTexels / layer);
            break;
        }
        if (e.x > box.x && e.x >= e.y) {
            e.x = std::max(box.x, e.x - unit);
        } else if (e.y > box.y) {
            e.y = std::max(box.y, e.y - unit);
        } else {
            break; // not even one box of the largest within maxTexels
        }
    }
    return e;
}

} // namespace lucent
