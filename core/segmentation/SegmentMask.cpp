#include "core/segmentation/SegmentMask.h"

#include <bit>
#include <stdexcept>

namespace lucent {

SegmentMask::SegmentMask(const glm::ivec3& dims) : dims_(dims) {
    if (dims.x < 0 || dims.y < 0 || dims.z < 0) {
        throw std::invalid_argument("SegmentMask: negative dimensions");
    }
    size_ = static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y) *
            static_cast<std::size_t>(dims.z);
    words_.assign((size_ + 63) / 64, 0);
}

glm::ivec3 SegmentMask::voxelOf(std::size_t index) const {
    const std::size_t nx = static_cast<std::size_t>(dims_.x);
    const std::size_t nxy = nx * static_cast<std::size_t>(dims_.y);
    return {static_cast<int>(index % nx), static_cast<int>((index % nxy) / nx),
            static_cast<int>(index / nxy)};
}

std::size_t SegmentMask::count() const {
    std::size_t n = 0;
    for (const std::uint64_t w : words_) {
        n += static_cast<std::size_t>(std::popcount(w));
    }
    return n;
}

SegmentMask::Bounds SegmentMask::bounds() const {
    Bounds b{dims_, glm::ivec3(-1)};
    forEachSet([&](std::size_t i) {
        const glm::ivec3 v = voxelOf(i);
        b.lo = glm::min(b.lo, v);
        b.hi = glm::max(b.hi, v);
    });
    return b;
}

bool SegmentMask::any() const {
    for (const std::uint64_t w : words_) {
        if (w != 0) {
            return true;
        }
    }
    return false;
}

void SegmentMask::checkSame(const SegmentMask& other) const {
    if (other.dims_ != dims_) {
        throw std::invalid_argument("SegmentMask: the two masks lie on different grids");
    }
}

void SegmentMask::clearTail() {
    if (const std::size_t used = size_ & 63; used != 0 && !words_.empty()) {
        words_.back() &= (std::uint64_t{1} << used) - 1;
    }
}

SegmentMask& SegmentMask::operator|=(const SegmentMask& other) {
    checkSame(other);
    for (std::size_t w = 0; w < words_.size(); ++w) {
        words_[w] |= other.words_[w];
    }
    return *this;
}

SegmentMask& SegmentMask::operator&=(const SegmentMask& other) {
    checkSame(other);
    for (std::size_t w = 0; w < words_.size(); ++w) {
        words_[w] &= other.words_[w];
    }
    return *this;
}

SegmentMask& SegmentMask::subtract(const SegmentMask& other) {
    checkSame(other);
    for (std::size_t w = 0; w < words_.size(); ++w) {
        words_[w] &= ~other.words_[w];
    }
    return *this;
}

SegmentMask& SegmentMask::invert() {
    for (std::uint64_t& w : words_) {
        w = ~w;
    }
    clearTail();
    return *this;
}

} // namespace lucent
