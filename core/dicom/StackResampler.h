#pragma once

#include "core/dicom/StackGeometry.h"
#include "core/volume/Volume.h"

namespace lucent {

// Resamples a decoded stack (columns x rows x kept images, in plan.order) onto
// plan.geometry: bilinear in each image plane, linear between neighbouring
// images along the normal. Voxels that no image covers get padValue.
// Integer volumes are rounded to the nearest integer.
Volume resampleStack(const Volume& stack, const StackPlan& plan, double padValue);

} // namespace lucent
