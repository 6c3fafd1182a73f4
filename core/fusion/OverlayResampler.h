#pragma once
// The overlay of a fused view resampled where the base is: through a 4x4 that maps a
// point in the base series' patient LPS mm to the same anatomy in the overlay's LPS mm
// (a registration's fixedToMoving with the base as the fixed series; the identity for
// two series of one Frame of Reference).

#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "core/mpr/PlaneSampler.h"
#include "core/mpr/RoiStatistics.h"
#include "core/volume/Volume.h"

namespace lucent {

// Where the overlay has no value (outside its volume): drawn as the base alone.
inline constexpr float kOverlayFill = std::numeric_limits<float>::quiet_NaN();

// The base plane in the overlay's space: its centre mapped and its axes through the
// linear part. For a rigid transform it is the same plane of anatomy, pixel for pixel;
// for an affine one its pixels are still the mapped points (its slab goes along the
// mapped plane's normal, the base's thickness).
SlicePlane overlayPlane(const SlicePlane& base, const glm::dmat4& baseToOverlay);

// The overlay's values at the base plane's pixels (trilinear, the plane's slab settings,
// `fill` outside the overlay), row-major as sampleImage returns them.
std::vector<float> sampleOverlay(const Volume& overlay, const SlicePlane& base,
                                 const glm::dmat4& baseToOverlay, float fill = kOverlayFill);

// An ellipse ROI drawn on the base plane, measured in the overlay: the same lattice
// points mapped into the overlay (ellipseStatistics there).
RoiStatistics overlayEllipseStatistics(const Volume& overlay, const SlicePlane& base,
                                       const EllipseRoi& ellipse, const glm::dmat4& baseToOverlay,
                                       double spacing = 0.0);

// The overlay resampled (trilinear) onto `target`'s grid as Float32: voxel (i, j, k) is the
// overlay at baseToOverlay(target.toPatient(i, j, k)); `fill` outside. Modality, series
// description and Frame of Reference of the overlay are kept (the grid is the target's).
// For 3D fusion and lucent-cli convert.
Volume resampleOverlay(const Volume& overlay, const VolumeGeometry& target,
                       const glm::dmat4& baseToOverlay, float fill = kOverlayFill);

} // namespace lucent
