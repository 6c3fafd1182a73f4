#pragma once

#include <vector>

#include "core/volume/Volume.h"

namespace lucent {

// Cubic B-spline coefficients of a volume (Unser, Aldroubi & Eden 1993): the
// B-spline through these coefficients interpolates the voxels exactly. Three
// separable passes of the causal/anticausal recursive filter with pole
// sqrt(3) - 2 and mirror boundaries; parallel over lines.
template <class Real> std::vector<Real> bsplineCoefficients(const Volume& volume);

extern template std::vector<float> bsplineCoefficients<float>(const Volume&);
extern template std::vector<double> bsplineCoefficients<double>(const Volume&);

} // namespace lucent
