#include "core/segmentation/SegmentSurface.h"

#include <cmath>
#include <stdexcept>

namespace lucent {
namespace {

constexpr std::int16_t kInside = 100; // the mask's voxels; outside 0, contoured at 50

} // namespace

SurfaceResult segmentSurface(const SegmentMask& mask, const VolumeGeometry& grid,
                             const SegmentSurfaceOptions& options, const std::string& name) {
    if (mask.dims() != grid.dims) {
        throw std::invalid_argument("segment surface: the mask of '" + name +
                                    "' lies on another grid");
    }
    auto [lo, hi] = mask.bounds();
    if (lo.x > hi.x) {
        throw std::runtime_error("segment '" + name + "' is empty: no surface");
    }
    // The smoothing reaches 3 sigma; one more voxel keeps every crossing inside the box.
    const glm::ivec3 reach(int(std::ceil(3.0 * options.sigma)) + 1);
    lo = glm::max(lo - reach, glm::ivec3(0));
    hi = glm::min(hi + reach, grid.dims - 1);
    VolumeGeometry box = grid;
    box.dims = hi - lo + 1;
    box.origin = grid.toPatient(glm::dvec3(lo));
    Volume field(box, VoxelType::Int16);
    auto voxels = field.voxels<std::int16_t>();
    std::size_t at = 0;
    for (int k = lo.z; k <= hi.z; ++k) {
        for (int j = lo.y; j <= hi.y; ++j) {
            for (int i = lo.x; i <= hi.x; ++i, ++at) {
                voxels[at] = mask.at(i, j, k) ? kInside : 0;
            }
        }
    }
    // The iso value must lie within the field's values: a mask filling its box (a grid
    // wholly set) has no 0, and the virtual outside layer closes the surface all the same.
    if (voxels[0] == kInside) {
        voxels[0] = kInside - 1;
    }
    SurfaceRequest request;
    request.iso = kInside / 2.0;
    request.maskSigma = options.sigma;
    request.smoothIterations = options.smoothIterations;
    request.decimate = options.decimate;
    return makeSurface(field, request);
}

} // namespace lucent
