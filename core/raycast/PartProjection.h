#pragma once
// Compositing the projections of a volume's parts (RenderResult::projection):
// MIP and MinIP keep the part whose value wins, which a depth compositor does
// when the value is encoded as depth; the average divides the parts' summed
// samples by their summed count.

#include <glm/glm.hpp>

#include "core/scene/RenderDescription.h"

namespace lucent {

// A depth in [0, 1) that is smaller the more the value wins (MIP: larger
// values, MinIP: smaller ones), over the volume's value range [lo, hi]; 1 (a
// depth compositor's "nothing here") where the ray took no sample.
float projectionDepth(RenderMode mode, glm::vec2 projection, double lo, double hi);

// The premultiplied colour of the average sum / count under the transfer
// function (transparent where count is 0).
glm::vec4 averageColour(const TransferFunction& tf, glm::vec2 sumAndCount);

} // namespace lucent
