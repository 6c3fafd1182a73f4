#pragma once
// The reader's nudge of a fused overlay: its content moved on the screen by a shift and a
// turn, folded into the base -> overlay transform (which the store then keeps).

#include <glm/glm.hpp>

namespace lucent {

// The transform after the overlay's content moved by `shiftMm` (base LPS mm) and turned by
// `angleRadians` about `axis` through `centre` (the turn first, then the shift): what was
// drawn at base point p is drawn at move(p). Returns baseToOverlay * move^-1.
glm::dmat4 nudgedTransform(const glm::dmat4& baseToOverlay, const glm::dvec3& shiftMm,
                           double angleRadians = 0.0, const glm::dvec3& axis = {0.0, 0.0, 1.0},
                           const glm::dvec3& centre = glm::dvec3(0.0));

} // namespace lucent
