#include "core/scene/ViewFrame.h"

#include <algorithm>
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

PixelRect pixelsOfBox(const VolumeGeometry& g, const ViewFrame& frame, glm::dvec3 lo, glm::dvec3 hi,
                      int width, int height) {
    const PixelRect all{0, 0, width - 1, height - 1};
    double sxLo = HUGE_VAL, sxHi = -HUGE_VAL, syLo = HUGE_VAL, syHi = -HUGE_VAL;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 corner((c & 1) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y,
                                (c & 4) != 0 ? hi.z : lo.z);
        const glm::dvec3 v = g.toPatient(corner) - frame.eye;
        const double depth = glm::dot(v, frame.forward);
        if (!(depth > 1e-6 * glm::length(v))) {
            return all;
        }
        const double sx = glm::dot(v, frame.right) / depth, sy = glm::dot(v, frame.up) / depth;
        sxLo = std::min(sxLo, sx), sxHi = std::max(sxHi, sx);
        syLo = std::min(syLo, sy), syHi = std::max(syHi, sy);
    }
    // ViewFrame::screenX and screenY solved for the pixel.
    const double ax = frame.tanHalfFov * frame.aspect, ay = frame.tanHalfFov;
    auto column = [&](double sx) { return (sx / ax + 1.0) * 0.5 * width - 0.5; };
    auto row = [&](double sy) { return (1.0 - sy / ay) * 0.5 * height - 0.5; };
    const double limit = 4.0 * double(std::max(width, height));
    auto pixel = [&](double p) { return int(std::clamp(p, -limit, limit)); };
    PixelRect r;
    r.x0 = std::max(0, pixel(std::floor(column(sxLo))) - 2);
    r.x1 = std::min(width - 1, pixel(std::ceil(column(sxHi))) + 2);
    r.y0 = std::max(0, pixel(std::floor(row(syHi))) - 2);
    r.y1 = std::min(height - 1, pixel(std::ceil(row(syLo))) + 2);
    return r;
}

} // namespace lucent
