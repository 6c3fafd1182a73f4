#pragma once
// One segment's voxels on its series' grid, one bit each (a 512x512x140 CT: 4.6 MB), i
// fastest, then j, then k, as Volume stores its voxels.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

class SegmentMask {
public:
    SegmentMask() = default;
    explicit SegmentMask(const glm::ivec3& dims);

    const glm::ivec3& dims() const { return dims_; }
    std::size_t size() const { return size_; }
    std::size_t linearIndex(int i, int j, int k) const {
        return static_cast<std::size_t>(i) +
               static_cast<std::size_t>(dims_.x) *
                   (static_cast<std::size_t>(j) +
                    static_cast<std::size_t>(dims_.y) * static_cast<std::size_t>(k));
    }
    glm::ivec3 voxelOf(std::size_t index) const;
    bool inside(const glm::ivec3& v) const {
        return v.x >= 0 && v.y >= 0 && v.z >= 0 && v.x < dims_.x && v.y < dims_.y && v.z < dims_.z;
    }

    bool get(std::size_t index) const { return (words_[index >> 6] >> (index & 63)) & 1u; }
    bool at(int i, int j, int k) const { return get(linearIndex(i, j, k)); }
    void set(std::size_t index, bool on = true) {
        const std::uint64_t bit = std::uint64_t{1} << (index & 63);
        words_[index >> 6] = on ? (words_[index >> 6] | bit) : (words_[index >> 6] & ~bit);
    }

    std::size_t count() const;
    bool any() const;
    // The smallest box of voxels holding every voxel set, corners inclusive; hi < lo on
    // every axis when none is set.
    struct Bounds {
        glm::ivec3 lo;
        glm::ivec3 hi;
        bool empty() const { return hi.x < lo.x; }
    };
    Bounds bounds() const;

    // Logical operators; both masks must have the same dims (std::invalid_argument).
    SegmentMask& operator|=(const SegmentMask& other); // add
    SegmentMask& operator&=(const SegmentMask& other); // intersect
    SegmentMask& subtract(const SegmentMask& other);
    SegmentMask& invert();
    bool operator==(const SegmentMask& other) const = default;

    // Calls f(index) for every voxel set, in increasing index order.
    template <class F> void forEachSet(F&& f) const {
        for (std::size_t w = 0; w < words_.size(); ++w) {
            std::uint64_t bits = words_[w];
            while (bits != 0) {
                const int b = std::countr_zero(bits);
                f(w * 64 + static_cast<std::size_t>(b));
                bits &= bits - 1;
            }
        }
    }

    std::span<const std::uint64_t> words() const { return words_; }

private:
    void checkSame(const SegmentMask& other) const;
    void clearTail();

    glm::ivec3 dims_{0};
    std::size_t size_ = 0;
    std::vector<std::uint64_t> words_;
};

} // namespace lucent
