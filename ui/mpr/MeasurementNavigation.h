#pragma once

#include <optional>

#include <QString>

#include "core/measure/Measurement.h"
#include "core/volume/Volume.h"

namespace lucent {

class MprCursor;

// Where a measurement lies, as the list shows it and the views go to it.

// The middle of its points (patient LPS mm).
glm::dvec3 measurementCentre(const Measurement& m);

// "Axial", "Coronal" or "Sagittal" for a plane along the patient axes, else "Oblique".
QString measurementPlaneName(const Measurement& m);

// The 1-based slice of the volume it was drawn on, when its plane is one of the
// volume's slices (its normal along a volume axis); none for an oblique plane.
std::optional<int> measurementSlice(const Measurement& m, const VolumeGeometry& geometry);

// Moves the linked views to the measurement: the crosshair to its centre, so that the
// view whose normal is m's shows its plane; for a plane that no view shows now, the
// planes are turned (MprCursor rotations) so that the nearest orientation's view does.
void showMeasurement(MprCursor& cursor, const Measurement& m);

} // namespace lucent
