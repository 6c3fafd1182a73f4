#pragma once
// The clip box on the 3D view: its edges and the centres of its six faces
// projected with the view's camera, which face handle a point hits, and the
// clip box a drag of a handle gives (the face follows the mouse along its axis).
// Plain geometry over core's ViewFrame: no widget, no GL.

#include <QPointF>
#include <QSizeF>

#include <array>
#include <optional>
#include <utility>

#include "core/scene/RenderDescription.h"

namespace lucent {

struct ClipHandle {
    int axis = 0;         // 0 i, 1 j, 2 k
    int side = 0;         // 0 the low face, 1 the high face
    bool visible = false; // in front of the eye
    QPointF screen;       // the face centre, in view pixels
    QPointF perVoxel;     // how far the centre moves on screen per voxel along the axis
};

using ClipHandles = std::array<ClipHandle, 6>; // i lo, i hi, j lo, j hi, k lo, k hi
using ClipEdges = std::array<std::pair<QPointF, QPointF>, 12>;

// The clip box within the volume's voxel centres [0, dims - 1].
ClipBox effectiveClip(const ClipBox& clip, glm::ivec3 dims);

// For a view of `size` (pixels) showing the volume with `camera`.
ClipHandles clipHandles(const VolumeGeometry& geometry, const Camera& camera, const ClipBox& clip,
                        QSizeF size);
// Edges with an end behind the eye are left as (0,0)-(0,0).
ClipEdges clipEdges(const VolumeGeometry& geometry, const Camera& camera, const ClipBox& clip,
                    QSizeF size);

// The visible handle nearest to `point` within `radius` pixels.
std::optional<int> hitClipHandle(const ClipHandles& handles, QPointF point, double radius);

// `start` with handle's face moved by the drag `delta` (pixels), to whole
// voxels, kept inside the volume and on its side of the opposite face.
ClipBox dragClipFace(const ClipBox& start, const ClipHandle& handle, QPointF delta,
                     glm::ivec3 dims);

} // namespace lucent
