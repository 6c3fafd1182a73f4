#pragma once
// How many voxels around its box a part of a volume needs (VolumePart.h) so
// that its samples, gradients and B-spline coefficients equal the whole
// volume's: what a ray caster of the part reads beyond the box.

#include <cmath>

#include "core/scene/RenderDescription.h"

namespace lucent {

// The cubic B-spline prefilter is a recursive filter over whole lines (pole
// sqrt(3) - 2, |z| = 0.268): a part that prefilters its own voxels has
// coefficients that differ from the whole volume's by about |z|^h times the
// data's range at h voxels from its edge. 12 voxels: 1.4e-7 of the range
// (0.3 mHU over a CT's 2000 HU), far below what an 8-bit image shows.
constexpr int kCubicPrefilterHalo = 12;

// The halo for sampling with `interpolation` at steps up to `maxStep` voxels:
// a trilinear or nearest sample reads the voxels around it, its gradient one
// more on each side (2); the sample before a shared face that iso crossings
// and pre-integrated segments start from lies a step outside; a cubic
// sample and its gradient read two voxels each side, plus the prefilter's
// halo.
inline int partHalo(Interpolation interpolation, double maxStep) {
    const int base = 2 + int(std::ceil(maxStep));
    return interpolation == Interpolation::Cubic ? base + 1 + kCubicPrefilterHalo : base;
}

} // namespace lucent
