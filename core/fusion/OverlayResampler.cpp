#include "core/fusion/OverlayResampler.h"

#include <algorithm>

namespace lucent {

SlicePlane overlayPlane(const SlicePlane& base, const glm::dmat4& baseToOverlay) {
    const glm::dmat3 linear(baseToOverlay);
    SlicePlane p = base;
    p.centre = glm::dvec3(baseToOverlay * glm::dvec4(base.centre, 1.0));
    p.u = linear * base.u;
    p.v = linear * base.v;
    return p;
}

std::vector<float> sampleOverlay(const Volume& overlay, const SlicePlane& base,
                                 const glm::dmat4& baseToOverlay, float fill) {
    return sampleImage(overlay, overlayPlane(base, baseToOverlay), fill);
}

RoiStatistics overlayEllipseStatistics(const Volume& overlay, const SlicePlane& base,
                                       const EllipseRoi& ellipse, const glm::dmat4& baseToOverlay,
                                       double spacing) {
    // The lattice is laid on the base plane (ellipseStatistics projects the centre onto
    // it first); mapping plane and centre together maps every lattice point.
    const glm::dvec3 onPlane = ellipse.centre - base.normal() * base.distance(ellipse.centre);
    EllipseRoi mapped = ellipse;
    mapped.centre = glm::dvec3(baseToOverlay * glm::dvec4(onPlane, 1.0));
    SlicePlane plane = overlayPlane(base, baseToOverlay);
    plane.centre = mapped.centre; // on the mapped plane; the distance projected out is 0
    return ellipseStatistics(overlay, plane, mapped, spacing);
}

Volume resampleOverlay(const Volume& overlay, const VolumeGeometry& target,
                       const glm::dmat4& baseToOverlay, float fill) {
    Volume out(target, VoxelType::Float32);
    static_cast<SeriesInfo&>(out) = static_cast<const SeriesInfo&>(overlay);
    if (target.voxelCount() == 0) {
        return out;
    }
    // Each target slice as a plane whose pixel (x, y) is voxel (x, y, k): axes scaled by
    // the spacing, a pixel size of 1.
    SlicePlane slice;
    slice.u = glm::dvec3(target.direction[0]) * target.spacing.x;
    slice.v = glm::dvec3(target.direction[1]) * target.spacing.y;
    slice.pixelSize = 1.0;
    slice.width = target.dims.x;
    slice.height = target.dims.y;
    const std::span<float> voxels = out.voxels<float>();
    const std::size_t perSlice = static_cast<std::size_t>(target.dims.x) * target.dims.y;
    for (int k = 0; k < target.dims.z; ++k) {
        slice.centre = target.toPatient(
            glm::dvec3(0.5 * (target.dims.x - 1), 0.5 * (target.dims.y - 1), double(k)));
        const std::vector<float> values = sampleOverlay(overlay, slice, baseToOverlay, fill);
        std::copy(values.begin(), values.end(), voxels.begin() + k * perSlice);
    }
    return out;
}

} // namespace lucent
