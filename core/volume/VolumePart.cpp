#include "core/volume/VolumePart.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace lucent {

namespace {

std::string text(glm::ivec3 v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) +
           ")";
}

} // namespace

std::pair<glm::ivec3, glm::ivec3> partVoxels(const PartBox& owned, glm::ivec3 dims, int halo) {
    const glm::ivec3 first = glm::max(owned.lo - halo, glm::ivec3(0));
    const glm::ivec3 last = glm::min(owned.hi + 1 + halo, dims);
    return {first, last};
}

VolumeGeometry partGeometry(const VolumeGeometry& whole, glm::ivec3 first, glm::ivec3 dims) {
    VolumeGeometry g = whole;
    g.dims = dims;
    g.origin = whole.toPatient(glm::dvec3(first));
    return g;
}

Volume cutPart(const Volume& whole, glm::ivec3 first, glm::ivec3 last) {
    const glm::ivec3 dims = whole.dims();
    if (glm::any(glm::lessThan(first, glm::ivec3(0))) || glm::any(glm::greaterThan(last, dims)) ||
        glm::any(glm::greaterThanEqual(first, last))) {
        throw std::invalid_argument("part " + text(first) + " .. " + text(last) +
                                    " is empty or leaves the volume of " + text(dims) + " voxels");
    }
    const glm::ivec3 size = last - first;
    Volume part(partGeometry(whole.geometry(), first, size), whole.type());
    static_cast<SeriesInfo&>(part) = static_cast<const SeriesInfo&>(whole);
    const std::size_t bytes = voxelSize(whole.type());
    const std::size_t row = std::size_t(size.x) * bytes;
    const std::byte* src = whole.bytes().data();
    std::byte* dst = part.bytes().data();
    for (int k = 0; k < size.z; ++k) {
        for (int j = 0; j < size.y; ++j) {
            std::memcpy(dst + (std::size_t(k) * size.y + j) * row,
                        src + whole.linearIndex(first.x, first.y + j, first.z + k) * bytes, row);
        }
    }
    return part;
}

} // namespace lucent
