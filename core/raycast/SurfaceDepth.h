#pragma once
// Where the surface seen at a place of a rendered image lies in the patient:
// what a teaching session's marks are anchored on, so that they stay on the
// anatomy when the view turns.

#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/RenderDescription.h"

namespace lucent {

// A pixel is "half made" where the opacity its ray has accumulated, front to back,
// first reaches this: the surface it shows lies there.
inline constexpr double kSurfaceOpacity = 0.5;

// The LPS point (mm) of the surface seen at `fraction` of the image of `description`
// ((0, 0) its top-left corner, (1, 1) the bottom-right; the ray is the one the CPU
// ray caster casts through that place): the ray enters the volume and clip box as the
// caster's rays do and takes the caster's samples (t_entry + n dt). DVR: the first
// sample at which the accumulated opacity (post-classification, corrected for dt)
// reaches kSurfaceOpacity (or the early termination, if lower). Isosurface: the first
// crossing of the iso value. MIP and MinIP: the sample of the maximum or minimum, when
// the transfer function gives it at least kSurfaceOpacity. Nothing where the ray
// misses the box, never gets there, or in average mode (no surface). Linear
// interpolation is used whatever the description's filter (a cubic or nearest render
// moves the point by less than a voxel). description.volume must be set.
std::optional<glm::dvec3> surfacePoint(const RenderDescription& description, glm::dvec2 fraction);

// The points of one mark placed at `fractions` of the image, anchored in the patient:
// each at its surfacePoint; one with no surface on the plane facing the viewer at the
// depth of the first point that has one (or, when none has, of the point the camera
// looks at), so that a mark drawn across the silhouette keeps its shape.
std::vector<glm::dvec3> surfaceAnchors(const RenderDescription& description,
                                       const std::vector<glm::dvec2>& fractions);

} // namespace lucent
