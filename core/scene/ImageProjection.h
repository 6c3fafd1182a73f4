#pragma once
// What a client needs to draw a patient point over a frame: the 3 x 4 matrix
// that takes (x, y, z, 1) in LPS mm to (u w, v w, w), u and v the point's place
// as fractions of the image (0, 0 its top-left corner, 1, 1 the bottom-right),
// w its depth along the view. The inverse of ViewFrame::rayDirection: the ray
// of pixel (x, y) projects to u = (x + 0.5) / width, v = (y + 0.5) / height.

#include <array>
#include <optional>

#include <glm/glm.hpp>

#include "core/scene/ViewFrame.h"

namespace lucent {

// Row-major: rows u w, v w, w.
using ImageProjection = std::array<double, 12>;

ImageProjection imageProjection(const ViewFrame& frame);

// (u, v) of an LPS point; nothing when it lies at or behind the eye.
std::optional<glm::dvec2> projectToImage(const ImageProjection& projection, const glm::dvec3& lps);

// The unit ray of the image fraction (u, v) (ViewFrame::rayDirection of its pixel).
glm::dvec3 rayThroughFraction(const ViewFrame& frame, glm::dvec2 fraction, int width, int height);

} // namespace lucent
