#pragma once
// For the pointer and mark tests: the demo head CT (Debian's invesalius-examples,
// the study the workstation opens on a fresh machine) and whether a point lies
// on its bone.

#include <QString>

#include <algorithm>
#include <cmath>

#include "core/volume/Volume.h"

namespace lucent::test {

inline const QString kDemoHead = "/usr/share/doc/invesalius-examples/examples/Cranium.inv3";
inline const char kDemoHeadMissing[] =
    "the demo head CT is not installed (apt-get install invesalius-examples: "
    "/usr/share/doc/invesalius-examples/examples/Cranium.inv3)";

// The largest voxel value within `radiusMm` of an LPS point (-inf outside the volume).
inline double maxValueNear(const Volume& v, const glm::dvec3& lps, double radiusMm) {
    const VolumeGeometry& g = v.geometry();
    const glm::ivec3 c(glm::round(g.toIndex(lps)));
    const glm::ivec3 r(glm::ceil(radiusMm / g.spacing));
    double best = -INFINITY;
    for (int k = c.z - r.z; k <= c.z + r.z; ++k) {
        for (int j = c.y - r.y; j <= c.y + r.y; ++j) {
            for (int i = c.x - r.x; i <= c.x + r.x; ++i) {
                if (i < 0 || j < 0 || k < 0 || i >= g.dims.x || j >= g.dims.y || k >= g.dims.z ||
                    glm::length(g.toPatient(glm::dvec3(i, j, k)) - lps) > radiusMm) {
                    continue;
                }
                best = std::max(best, v.value(i, j, k));
            }
        }
    }
    return best;
}

} // namespace lucent::test
