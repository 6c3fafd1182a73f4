#include "core/scene/ViewFrame.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace lucent {

double volumeRadius(const VolumeGeometry& g) {
    const glm::dvec3 c = volumeCentre(g);
    double r = 0.0;
    for (int n = 0; n < 8; ++n) {
        const glm::dvec3 corner((n & 1) ? g.dims.x - 1 : 0, (n & 2) ? g.dims.y - 1 : 0,
                                (n & 4) ? g.dims.z - 1 : 0);
        r = std::max(r, glm::length(g.toPatient(corner) - c));
    }
    return std::max(r, 1e-6);
}

double fitDistance(const VolumeGeometry& geometry, const Camera& camera, int width, int height) {
    const double aspect = static_cast<double>(width) / static_cast<double>(height);
    const double halfFov = glm::radians(camera.fieldOfView) * 0.5;
    // The bounding sphere just fits the narrower side of the view.
    const double fitHalf = std::min(halfFov, std::atan(std::tan(halfFov) * aspect));
    return volumeRadius(geometry) / std::sin(fitHalf);
}

ViewFrame makeViewFrame(const VolumeGeometry& geometry, const Camera& camera, int width,
                        int height) {
    ViewFrame f;
    // Elevation about the left-right axis first, then azimuth about the head-foot axis.
    const glm::dmat4 rot = glm::rotate(glm::dmat4(1.0), glm::radians(camera.azimuth), {0, 0, 1}) *
                           glm::rotate(glm::dmat4(1.0), glm::radians(camera.elevation), {1, 0, 0});
    const glm::dmat3 r(rot);
    f.forward = glm::normalize(r * glm::dvec3(0, 1, 0));
    f.right = glm::normalize(r * glm::dvec3(1, 0, 0));
    f.up = glm::normalize(r * glm::dvec3(0, 0, 1));
    f.aspect = static_cast<double>(width) / static_cast<double>(height);
    const double halfFov = glm::radians(camera.fieldOfView) * 0.5;
    const double distance =
        camera.distance > 0.0 ? camera.distance : fitDistance(geometry, camera, width, height);
    f.tanHalfFov = std::tan(halfFov) / camera.zoom;
    const glm::dvec3 target =
        volumeCentre(geometry) + f.right * camera.panRight + f.up * camera.panUp;
    f.eye = target - f.forward * distance;
    return f;
}

} // namespace lucent
