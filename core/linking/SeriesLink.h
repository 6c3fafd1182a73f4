#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {

// How a patient position in one series (a) is found in another (b), for linked
// scrolling and crosshairs between viewports.
//   SamePosition: both share a Frame of Reference; a point is the same point in b.
//   Registered:   different Frames of Reference aligned by registration: point_b =
//                 transform * point_a (a rigid 4x4, LPS mm).
//   Offset:       different Frames of Reference (a prior, another scanner) joined by
//                 an offset the reader set once by clicking the same anatomy in both
//                 ("link here"): point_b = point_a + offset.
//   None:         no relation known; `reason` says why, for a notice.
struct SeriesLink {
    enum class Kind { SamePosition, Registered, Offset, None };
    Kind kind = Kind::None;
    glm::dvec3 offset{0.0};    // b - a, LPS mm (Offset only)
    glm::dmat4 transform{1.0}; // a -> b, LPS mm (Registered only)
    std::string reason;        // None only

    bool linked() const { return kind != Kind::None; }
    // The link from b to a.
    SeriesLink reversed() const;
    // Where a point of a is in b, and a direction of a (a plane normal) in b.
    glm::dvec3 map(const glm::dvec3& pointA) const;
    glm::dvec3 mapDirection(const glm::dvec3& directionA) const;
};

// The link between two series: SamePosition for the same series; else Registered when a
// transform a -> b is known (a registration, or a nudge of a fused overlay: it wins over a
// shared Frame of Reference); else SamePosition when both have the same non-empty Frame of
// Reference UID; else Offset when an offset is known (b - a); else None with the reason.
SeriesLink linkSeries(const SeriesInfo& a, const SeriesInfo& b,
                      const std::optional<glm::dvec3>& knownOffset,
                      const std::optional<glm::dmat4>& knownTransform = std::nullopt);

// The offset that "link here" records: the same anatomy clicked at pointA in a
// and at pointB in b.
inline glm::dvec3 linkHereOffset(const glm::dvec3& pointA, const glm::dvec3& pointB) {
    return pointB - pointA;
}

// Planes whose normals differ by more than this do not scroll together: a slice
// position means nothing along a direction the other plane does not step in.
inline constexpr double kParallelToleranceDegrees = 5.0;

// Whether two plane normals are parallel (either sense) within toleranceDegrees.
bool planesParallel(const glm::dvec3& normalA, const glm::dvec3& normalB,
                    double toleranceDegrees = kParallelToleranceDegrees);
// The angle between two plane normals, degrees in 0..90 (the sense does not matter).
double planeAngleDegrees(const glm::dvec3& normalA, const glm::dvec3& normalB);

// `point` moved along `normal` onto the nearest slice of `geometry`: the index along
// the volume axis most aligned with the normal is rounded to a voxel centre and kept
// inside the volume; the position within the plane is unchanged. A linked view
// shows an acquired slice, never a blend of two.
glm::dvec3 nearestSlicePoint(const VolumeGeometry& geometry, const glm::dvec3& point,
                             const glm::dvec3& normal);

// Where a's point lands in b: mapped through the link, then onto b's nearest slice
// along `normal` (b's plane normal). Requires link.linked().
glm::dvec3 linkedPoint(const SeriesLink& link, const VolumeGeometry& b, const glm::dvec3& pointA,
                       const glm::dvec3& normal);

} // namespace lucent
