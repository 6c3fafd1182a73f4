#include "core/segmentation/SegmentBrush.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lucent {
namespace {

// The index box (clipped to the grid) holding the patient box [lo, hi]: max < min when none.
void indexBox(const VolumeGeometry& grid, const glm::dvec3& lo, const glm::dvec3& hi,
              glm::ivec3& first, glm::ivec3& last) {
    glm::dvec3 a(std::numeric_limits<double>::max()), b(-std::numeric_limits<double>::max());
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                           (corner & 4) ? hi.z : lo.z);
        const glm::dvec3 ijk = grid.toIndex(p);
        a = glm::min(a, ijk);
        b = glm::max(b, ijk);
    }
    first = glm::max(glm::ivec3(glm::floor(a)), glm::ivec3(0));
    last = glm::min(glm::ivec3(glm::ceil(b)), grid.dims - 1);
}

bool inSlab(const SliceSlab& slab, const glm::dvec3& offset) {
    const double d = glm::dot(offset, slab.normal);
    return d > -slab.halfThicknessMm && d <= slab.halfThicknessMm;
}

bool change(SegmentMask& mask, std::size_t at, bool on) {
    if (mask.get(at) == on) {
        return false;
    }
    mask.set(at, on);
    return true;
}

} // namespace

std::size_t paintBrush(SegmentMask& mask, const VolumeGeometry& grid, const glm::dvec3& centre,
                       double radiusMm, bool on, const std::optional<SliceSlab>& slab) {
    if (radiusMm < 0.0 || mask.dims() != grid.dims) {
        return 0;
    }
    glm::ivec3 first, last;
    indexBox(grid, centre - radiusMm, centre + radiusMm, first, last);
    const double r2 = radiusMm * radiusMm * (1.0 + 1e-12);
    std::size_t changed = 0;
    for (int k = first.z; k <= last.z; ++k) {
        for (int j = first.y; j <= last.y; ++j) {
            for (int i = first.x; i <= last.x; ++i) {
                const glm::dvec3 offset = grid.toPatient(glm::dvec3(i, j, k)) - centre;
                if (glm::dot(offset, offset) > r2 || (slab && !inSlab(*slab, offset))) {
                    continue;
                }
                changed += change(mask, mask.linearIndex(i, j, k), on) ? 1 : 0;
            }
        }
    }
    return changed;
}

std::size_t fillOutline(SegmentMask& mask, const VolumeGeometry& grid,
                        const std::vector<glm::dvec3>& outline, const SliceSlab& slab, bool on) {
    if (outline.size() < 3 || mask.dims() != grid.dims) {
        return 0;
    }
    // A basis of the slice: u along any direction not the normal, v = n x u.
    const glm::dvec3 n = glm::normalize(slab.normal);
    const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(helper, n));
    const glm::dvec3 v = glm::cross(n, u);
    const glm::dvec3 origin = outline.front();
    std::vector<glm::dvec2> polygon;
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const glm::dvec3& p : outline) {
        polygon.push_back({glm::dot(p - origin, u), glm::dot(p - origin, v)});
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    glm::ivec3 first, last;
    indexBox(grid, lo - slab.halfThicknessMm, hi + slab.halfThicknessMm, first, last);
    std::size_t changed = 0;
    for (int k = first.z; k <= last.z; ++k) {
        for (int j = first.y; j <= last.y; ++j) {
            for (int i = first.x; i <= last.x; ++i) {
                const glm::dvec3 offset = grid.toPatient(glm::dvec3(i, j, k)) - origin;
                if (!inSlab({n, slab.halfThicknessMm}, offset)) {
                    continue;
                }
                const glm::dvec2 q(glm::dot(offset, u), glm::dot(offset, v));
                bool in = false; // even-odd: crossings of a ray towards +u
                for (std::size_t a = 0, b = polygon.size() - 1; a < polygon.size(); b = a++) {
                    const glm::dvec2& pa = polygon[a];
                    const glm::dvec2& pb = polygon[b];
                    if ((pa.y > q.y) != (pb.y > q.y) &&
                        q.x < (pb.x - pa.x) * (q.y - pa.y) / (pb.y - pa.y) + pa.x) {
                        in = !in;
                    }
                }
                if (in) {
                    changed += change(mask, mask.linearIndex(i, j, k), on) ? 1 : 0;
                }
            }
        }
    }
    return changed;
}

} // namespace lucent
