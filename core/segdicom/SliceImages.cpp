#include "core/segdicom/SliceImages_p.h"

#include <cmath>

namespace lucent::segdicom {

int sliceAt(const VolumeGeometry& grid, const glm::dvec3& position) {
    const glm::dvec3 ijk = grid.toIndex(position);
    const double k = std::round(ijk.z);
    constexpr double kTolerance = 0.1; // voxels
    if (std::abs(ijk.x) > kTolerance || std::abs(ijk.y) > kTolerance ||
        std::abs(ijk.z - k) > kTolerance || k < 0.0 || k >= grid.dims.z) {
        return -1;
    }
    return static_cast<int>(k);
}

std::vector<const ReferencedImage*> imagesBySlice(const ReferencedSeries& series,
                                                  const VolumeGeometry& grid) {
    std::vector<const ReferencedImage*> slices(static_cast<std::size_t>(std::max(grid.dims.z, 0)),
                                               nullptr);
    for (const ReferencedImage& image : series.images) {
        if (image.frames != 1 || !sameOrientation(grid, image.rowDir, image.colDir)) {
            continue;
        }
        const int k = sliceAt(grid, image.position);
        if (k >= 0 && slices[static_cast<std::size_t>(k)] == nullptr) {
            slices[static_cast<std::size_t>(k)] = &image;
        }
    }
    return slices;
}

bool sameOrientation(const VolumeGeometry& grid, const glm::dvec3& rowDir,
                     const glm::dvec3& colDir) {
    constexpr double kTolerance = 1e-3; // of unit vectors: about 0.06 degrees
    return glm::length(glm::normalize(grid.direction[0]) - glm::normalize(rowDir)) < kTolerance &&
           glm::length(glm::normalize(grid.direction[1]) - glm::normalize(colDir)) < kTolerance;
}

} // namespace lucent::segdicom
