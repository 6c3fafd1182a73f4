#pragma once
// Which data values can contribute to an image: the test both ray casters use
// to leap over bricks and to keep empty bricks off the GPU.

#include <functional>
#include <utility>
#include <vector>

#include "core/scene/RenderDescription.h"
#include "core/scene/ViewFrame.h"

namespace lucent {

// What valueVisibility answers from: two descriptions with equal keys see
// the same values, so what was derived from one (visible cells, boxes) holds
// for the other. A colour or shading change leaves it as it is.
struct VisibilityKey {
    RenderMode mode = RenderMode::Dvr;
    double isoValue = 0.0;
    std::vector<OpacityPoint> opacity; // DVR only
    double widen = 0.0;                // of each range asked, for the table's lookups
    bool operator==(const VisibilityKey&) const = default;
};
VisibilityKey visibilityKey(const RenderDescription& desc, double tableLo, double tableHi,
                            int tableSize);
std::function<bool(double lo, double hi)> valueVisibility(const VisibilityKey& key);

// isVisible(lo, hi) for visibleBricks: whether any value in [lo, hi] can show.
// DVR: non-zero opacity; isosurface: the iso value inside; MIP, MinIP and
// average: always. tableSize is the size of the table the renderer classifies
// with (0 when it evaluates the transfer function exactly): the range is
// widened by one table cell, since a lookup mixes neighbouring entries.
std::function<bool(double lo, double hi)>
valueVisibility(const RenderDescription& desc, double tableLo, double tableHi, int tableSize);

// The range the classification tables cover: [lo, hi], or for a constant
// volume a range around lo wide enough to differ from it in double precision
// (lo + 1 is lo again for lo = 1e30).
std::pair<double, double> tableRange(double lo, double hi);

// What both ray casters divide gradients by before shading: the largest
// |value| of the volume (1 for an all-zero one). Shading needs only the
// gradient's direction; in these units its length neither overflows in float
// (values of 1e30) nor falls under the "no surface here" threshold because the
// data are small (values of 1e-30), and that threshold (1e-6) is relative to
// the data.
double gradientScale(double valueLo, double valueHi);

// The values outside which the transfer function's opacity is zero, widened
// by `tableCell` (infinite where the opacity never drops to zero).
std::pair<double, double> visibleValueRange(const TransferFunction& tf, double tableCell);

// Whether any ray of the view can reach a box of voxel centres (index space,
// closed): false only when the whole box lies behind the eye or beyond one edge
// of the image.
bool boxInView(const VolumeGeometry& geometry, const ViewFrame& frame, const glm::dvec3& lo,
               const glm::dvec3& hi);

} // namespace lucent
