#include "core/fusion/OverlayNudge.h"

#include <glm/gtc/matrix_transform.hpp>

namespace lucent {

glm::dmat4 nudgedTransform(const glm::dmat4& baseToOverlay, const glm::dvec3& shiftMm,
                           double angleRadians, const glm::dvec3& axis, const glm::dvec3& centre) {
    glm::dmat4 move = glm::translate(glm::dmat4(1.0), shiftMm);
    if (angleRadians != 0.0 && glm::length(axis) > 0.0) {
        move = move * glm::translate(glm::dmat4(1.0), centre) *
               glm::rotate(glm::dmat4(1.0), angleRadians, glm::normalize(axis)) *
               glm::translate(glm::dmat4(1.0), -centre);
    }
    return baseToOverlay * glm::inverse(move);
}

} // namespace lucent
