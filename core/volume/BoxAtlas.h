#pragma once
// Where boxes of different sizes sit in one 3D texture: a guillotine
// allocator over a fixed extent. A placed box takes a corner of the free box
// it fits best (the least volume left over) and the rest is cut into three
// free boxes; a released box is free again. Without merging, free space
// fragments over time: the caller repacks (a new atlas, largest boxes first)
// when a box no longer fits.

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

class BoxAtlas {
public:
    // Throws std::invalid_argument for an extent with a side below 1.
    explicit BoxAtlas(glm::ivec3 extent);

    glm::ivec3 extent() const { return extent_; }
    std::size_t texels() const;
    std::size_t usedTexels() const { return used_; }

    // Where a box of `size` goes, or nothing when no free box holds it.
    std::optional<glm::ivec3> place(glm::ivec3 size);
    // Frees a box that place() returned (origin and size as placed).
    void release(glm::ivec3 origin, glm::ivec3 size);

    // An extent for boxes holding `texels` in all, none larger than
    // `largest`, within maxSide per side: x and y whole multiples of the
    // largest box (about the cube root of the texels), z as deep as needed.
    // No more than maxTexels in all where the largest box still fits (z
    // shortened first, so the extent may then hold fewer than `texels`).
    // Throws std::length_error when maxSide^3 is not enough.
    static glm::ivec3 extentFor(std::size_t texels, glm::ivec3 largest, int maxSide,
                                std::size_t maxTexels = std::numeric_limits<std::size_t>::max());

private:
    struct Free {
        glm::ivec3 origin, size;
    };
    glm::ivec3 extent_;
    std::vector<Free> free_;
    std::size_t used_ = 0;
};

} // namespace lucent
