#pragma once
// Known transforms of a real volume, for the registration tests and the registration
// benchmark: a copy of a CT resampled (trilinear) under a known rigid or affine
// transform, an MR-like remapping of its intensities, and the target registration error
// over a grid of points inside the body.

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent::test {

// A rigid transform about the point c: x -> c + t + R (x - c), R from rotations about
// x, then y, then z (degrees).
glm::dmat4 rigidAbout(const glm::dvec3& c, const glm::dvec3& degrees, const glm::dvec3& t);

// An affine transform about c: x -> c + t + Rz(degreesZ) * Shear * Scale (x - c), where
// Scale = diag(scale) and Shear adds shearXY * y to x.
glm::dmat4 affineAbout(const glm::dvec3& c, const glm::dvec3& scale, double shearXY,
                       double degreesZ, const glm::dvec3& t);

// The anatomy of `fixed` moved by fixedToMoving, on fixed's grid (Float32), intensities
// through `map`: moving(y) = map(fixed(fixedToMoving^-1 y)), trilinear; air (-1024 HU)
// outside. The copy has `modality`, a new Frame of Reference (`frameOfReferenceUid`) and
// no series or study UID of its own.
Volume resampled(const Volume& fixed, const glm::dmat4& fixedToMoving,
                 const std::function<double(double)>& map, const std::string& modality,
                 const std::string& frameOfReferenceUid);

// MR-like and non-monotonic: air and bone dark, fat bright, soft tissue in between.
double mrLike(double hu);

// Every 10 mm in x, y and z over the fixed volume (two slices in from its ends), where
// the fixed CT is above -500 HU (inside the body).
std::vector<glm::dvec3> bodyGrid(const Volume& fixed);

struct Tre {
    double mean = 0.0;
    double max = 0.0;
};

// The distances between where `truth` and `found` put each point (fixed LPS mm).
Tre treOf(const std::vector<glm::dvec3>& points, const glm::dmat4& truth, const glm::dmat4& found);

} // namespace lucent::test
