#include "core/mpr/CrosshairSlice.h"

#include <algorithm>

namespace lucent {

SlicePlane crosshairPlane(const VolumeGeometry& geometry, Orientation orientation,
                          const glm::dvec3& crosshair, int width, int height,
                          const glm::dmat3& rotation, double zoom, const glm::dvec2& pan) {
    const bool none = geometry.dims.x <= 0 || geometry.dims.y <= 0 || geometry.dims.z <= 0;
    const glm::dvec3 mid = none ? crosshair : volumeCentre(geometry);
    SlicePlane p = standardPlane(geometry, orientation, mid, width, height);
    p.u = rotation * p.u;
    p.v = rotation * p.v;
    p.pixelSize /= zoom;
    const glm::dvec3 n = p.normal();
    p.centre = mid + n * glm::dot(crosshair - mid, n) + p.u * pan.x + p.v * pan.y;
    return p;
}

std::vector<std::uint8_t> windowedGrey(std::span<const float> samples, double center,
                                       double width) {
    std::vector<std::uint8_t> grey(samples.size());
    std::transform(samples.begin(), samples.end(), grey.begin(),
                   [&](float value) { return windowToGrey(value, center, width); });
    return grey;
}

glm::dvec3 clampToVolume(const VolumeGeometry& geometry, const glm::dvec3& point) {
    if (geometry.dims.x <= 0 || geometry.dims.y <= 0 || geometry.dims.z <= 0) {
        return point;
    }
    const glm::dvec3 ijk = glm::dvec3(geometry.patientToIndex() * glm::dvec4(point, 1.0));
    const glm::dvec3 inside = glm::clamp(ijk, glm::dvec3(0.0), glm::dvec3(geometry.dims - 1));
    return inside == ijk ? point : geometry.toPatient(inside);
}

} // namespace lucent
