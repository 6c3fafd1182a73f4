#include "core/linking/SeriesLink.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace lucent {

SeriesLink SeriesLink::reversed() const {
    SeriesLink back = *this;
    back.offset = -offset;
    back.transform = glm::inverse(transform);
    return back;
}

glm::dvec3 SeriesLink::map(const glm::dvec3& pointA) const {
    switch (kind) {
    case Kind::Registered:
        return glm::dvec3(transform * glm::dvec4(pointA, 1.0));
    case Kind::Offset:
        return pointA + offset;
    default:
        return pointA;
    }
}

glm::dvec3 SeriesLink::mapDirection(const glm::dvec3& directionA) const {
    return kind == Kind::Registered ? glm::dvec3(transform * glm::dvec4(directionA, 0.0))
                                    : directionA;
}

SeriesLink linkSeries(const SeriesInfo& a, const SeriesInfo& b,
                      const std::optional<glm::dvec3>& knownOffset,
                      const std::optional<glm::dmat4>& knownTransform) {
    SeriesLink link;
    const bool sameSeries = !a.seriesUid.empty() && a.seriesUid == b.seriesUid;
    const bool sameFrame =
        !a.frameOfReferenceUid.empty() && a.frameOfReferenceUid == b.frameOfReferenceUid;
    if (sameSeries) {
        link.kind = SeriesLink::Kind::SamePosition;
    } else if (knownTransform) {
        // Registered or nudged by the reader: this beats a shared Frame of Reference (a PET
        // and its CT that breathing put apart).
        link.kind = SeriesLink::Kind::Registered;
        link.transform = *knownTransform;
    } else if (sameFrame) {
        link.kind = SeriesLink::Kind::SamePosition;
    } else if (knownOffset) {
        link.kind = SeriesLink::Kind::Offset;
        link.offset = *knownOffset;
    } else {
        link.reason = "different Frames of Reference, not registered and no offset set: choose "
                      "Register, or click the same anatomy in both and choose Link Here";
    }
    return link;
}

double planeAngleDegrees(const glm::dvec3& normalA, const glm::dvec3& normalB) {
    const double la = glm::length(normalA);
    const double lb = glm::length(normalB);
    if (la == 0.0 || lb == 0.0) {
        return 90.0;
    }
    const double cosine = std::min(1.0, std::abs(glm::dot(normalA, normalB)) / (la * lb));
    return std::acos(cosine) * 180.0 / std::numbers::pi;
}

bool planesParallel(const glm::dvec3& normalA, const glm::dvec3& normalB, double toleranceDegrees) {
    return planeAngleDegrees(normalA, normalB) <= toleranceDegrees;
}

glm::dvec3 nearestSlicePoint(const VolumeGeometry& geometry, const glm::dvec3& point,
                             const glm::dvec3& normal) {
    if (geometry.voxelCount() == 0) {
        return point;
    }
    int axis = 0;
    double best = -1.0;
    for (int n = 0; n < 3; ++n) {
        const double along = std::abs(glm::dot(geometry.direction[n], normal));
        if (along > best) {
            best = along;
            axis = n;
        }
    }
    const glm::dvec3 ijk = geometry.toIndex(point);
    const double snapped =
        std::clamp(std::round(ijk[axis]), 0.0, static_cast<double>(geometry.dims[axis] - 1));
    // Move along the normal (not along the axis) so the in-plane position stays.
    const glm::dvec3 unit = glm::normalize(normal);
    const double indexPerMm = geometry.toIndex(point + unit)[axis] - ijk[axis];
    if (std::abs(indexPerMm) < 1e-9) {
        return point;
    }
    const double move = (snapped - ijk[axis]) / indexPerMm;
    return point + unit * move;
}

glm::dvec3 linkedPoint(const SeriesLink& link, const VolumeGeometry& b, const glm::dvec3& pointA,
                       const glm::dvec3& normal) {
    if (!link.linked()) {
        throw std::logic_error("linkedPoint: the series are not linked");
    }
    return nearestSlicePoint(b, link.map(pointA), normal);
}

} // namespace lucent
