#include "ui/volume/ClipBoxHandles.h"

#include <algorithm>
#include <cmath>

#include "core/scene/ViewFrame.h"

namespace lucent {

namespace {

// Where patient point p appears in a view of `size` pixels (pixel x spans [x, x + 1],
// as in core's ViewFrame); nullopt behind the eye.
std::optional<QPointF> project(const ViewFrame& f, const glm::dvec3& p, QSizeF size) {
    const glm::dvec3 rel = p - f.eye;
    const double z = glm::dot(rel, f.forward);
    if (z <= 1e-9) {
        return std::nullopt;
    }
    const double sx = glm::dot(rel, f.right) / (z * f.tanHalfFov * f.aspect);
    const double sy = glm::dot(rel, f.up) / (z * f.tanHalfFov);
    return QPointF((sx + 1.0) * 0.5 * size.width(), (1.0 - sy) * 0.5 * size.height());
}

ViewFrame frameFor(const VolumeGeometry& g, const Camera& camera, QSizeF size) {
    // Only the aspect matters for where points land; the size in pixels scales them.
    const int w = std::max(1, int(std::lround(size.width())));
    const int h = std::max(1, int(std::lround(size.height())));
    return makeViewFrame(g, camera, w, h);
}

} // namespace

ClipBox effectiveClip(const ClipBox& clip, glm::ivec3 dims) {
    ClipBox c;
    const glm::dvec3 last = glm::dvec3(glm::max(dims - 1, glm::ivec3(0)));
    c.lo = glm::clamp(clip.lo, glm::dvec3(0.0), last);
    c.hi = glm::clamp(clip.hi, c.lo, last);
    return c;
}

ClipHandles clipHandles(const VolumeGeometry& g, const Camera& camera, const ClipBox& clip,
                        QSizeF size) {
    const ViewFrame f = frameFor(g, camera, size);
    const ClipBox c = effectiveClip(clip, g.dims);
    ClipHandles handles;
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            ClipHandle& h = handles[std::size_t(2 * axis + side)];
            h.axis = axis;
            h.side = side;
            glm::dvec3 centre = 0.5 * (c.lo + c.hi);
            centre[axis] = side == 0 ? c.lo[axis] : c.hi[axis];
            glm::dvec3 step = centre;
            step[axis] += 1.0;
            const auto at = project(f, g.toPatient(centre), size);
            const auto next = project(f, g.toPatient(step), size);
            h.visible = at.has_value() && next.has_value();
            if (h.visible) {
                h.screen = *at;
                h.perVoxel = *next - *at;
            }
        }
    }
    return handles;
}

ClipEdges clipEdges(const VolumeGeometry& g, const Camera& camera, const ClipBox& clip,
                    QSizeF size) {
    const ViewFrame f = frameFor(g, camera, size);
    const ClipBox c = effectiveClip(clip, g.dims);
    const auto corner = [&](int n) {
        return glm::dvec3(n & 1 ? c.hi.x : c.lo.x, n & 2 ? c.hi.y : c.lo.y,
                          n & 4 ? c.hi.z : c.lo.z);
    };
    ClipEdges edges{};
    std::size_t e = 0;
    for (int n = 0; n < 8; ++n) {
        for (const int bit : {1, 2, 4}) {
            if ((n & bit) != 0) {
                continue;
            }
            const auto a = project(f, g.toPatient(corner(n)), size);
            const auto b = project(f, g.toPatient(corner(n | bit)), size);
            if (a && b) {
                edges[e] = {*a, *b};
            }
            ++e;
        }
    }
    return edges;
}

std::optional<int> hitClipHandle(const ClipHandles& handles, QPointF point, double radius) {
    std::optional<int> best;
    double bestDistance = radius;
    for (std::size_t n = 0; n < handles.size(); ++n) {
        if (!handles[n].visible) {
            continue;
        }
        const QPointF d = handles[n].screen - point;
        const double distance = std::hypot(d.x(), d.y());
        if (distance <= bestDistance) {
            bestDistance = distance;
            best = int(n);
        }
    }
    return best;
}

ClipBox dragClipFace(const ClipBox& start, const ClipHandle& handle, QPointF delta,
                     glm::ivec3 dims) {
    ClipBox c = effectiveClip(start, dims);
    const QPointF v = handle.perVoxel;
    const double length2 = v.x() * v.x() + v.y() * v.y();
    if (length2 < 1e-6) {
        return c; // the axis points at the eye: a drag cannot say how far
    }
    const double voxels = (delta.x() * v.x() + delta.y() * v.y()) / length2;
    const int a = handle.axis;
    const double last = std::max(0, dims[a] - 1);
    if (handle.side == 0) {
        c.lo[a] = std::clamp(std::round(c.lo[a] + voxels), 0.0, c.hi[a]);
    } else {
        c.hi[a] = std::clamp(std::round(c.hi[a] + voxels), c.lo[a], last);
    }
    return c;
}

} // namespace lucent
