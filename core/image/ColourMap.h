#pragma once
// The colour map of scalar fields on surfaces (SVR): viridis (van der Walt and
// Smith, matplotlib), perceptually uniform and readable in grey and by most
// colour-blind readers. One home for the mesh files' baked colours and the
// 3D view's colour bar.

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

namespace lucent {

// t in [0, 1] (clamped; NaN gives the low end), linear RGB in [0, 1].
glm::dvec3 viridis(double t);

// The colour of `value` over [lo, hi] (lo at the low end), as 8-bit RGB.
std::array<std::uint8_t, 3> viridisBytes(double value, double lo, double hi);

} // namespace lucent
