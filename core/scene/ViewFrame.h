#pragma once

#include <glm/glm.hpp>

#include "core/scene/RenderDescription.h"

namespace lucent {

// Where the camera is and which way each pixel's ray goes, in patient LPS mm.
struct ViewFrame {
    glm::dvec3 eye{0.0};
    glm::dvec3 forward{0.0, 1.0, 0.0}; // anterior view: looking from the front towards posterior
    glm::dvec3 right{1.0, 0.0, 0.0};   // patient's left appears on screen right
    glm::dvec3 up{0.0, 0.0, 1.0};      // head up
    double tanHalfFov = 0.0;
    double aspect = 1.0;

    // Unit direction of the ray through the centre of pixel (x, y); y = 0 is the top row.
    glm::dvec3 rayDirection(double x, double y, int width, int height) const {
        return direction(screenX(x, width), screenY(y, height));
    }
    // rayDirection in steps, for callers that share a column's or row's term.
    double screenX(double x, int width) const {
        return (2.0 * (x + 0.5) / width - 1.0) * tanHalfFov * aspect;
    }
    double screenY(double y, int height) const {
        return (1.0 - 2.0 * (y + 0.5) / height) * tanHalfFov;
    }
    glm::dvec3 direction(double sx, double sy) const {
        return glm::normalize(forward + right * sx + up * sy);
    }
};

ViewFrame makeViewFrame(const VolumeGeometry& geometry, const Camera& camera, int width,
                        int height);

// The eye's distance from the point looked at when Camera::distance is 0: the
// volume's bounding sphere just fits the narrower side of a view of this size.
double fitDistance(const VolumeGeometry& geometry, const Camera& camera, int width, int height);

// Pixels x0 .. x1, y0 .. y1 (inclusive).
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
};

// The pixels whose rays can meet the box lo .. hi (index space): the bounding
// rectangle of its corners on screen, two pixels wider than rounding could
// ever need; the whole image when a corner lies at or behind the eye.
PixelRect pixelsOfBox(const VolumeGeometry& g, const ViewFrame& frame, glm::dvec3 lo, glm::dvec3 hi,
                      int width, int height);

// Radius of the sphere around the voxel centres (centred on volumeCentre), in LPS mm.
double volumeRadius(const VolumeGeometry& geometry);

} // namespace lucent
