#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/mpr/PlaneSampler.h"
#include "core/mpr/RoiStatistics.h"
#include "core/pet/SuvStatistics.h"

namespace lucent {

// What a reader measures on a slice. Every kind is a list of patient points (LPS mm)
// with a fixed layout:
//   Distance       2 points: the ends
//   Angle          3 points: arm end, vertex, arm end
//   CobbAngle      4 points: the first line (0, 1), the second line (2, 3)
//   Arrow          2 points: tail, head (the head points at the finding); text
//   Bidirectional  4 points: long axis ends (0, 1), short axis ends (2, 3), as RECIST reads
//   Ellipse        4 points: the ends of the axis along the plane's u (0, 1) and of the
//                  axis along its v (2, 3); the values inside are in `statistics`
enum class MeasurementKind { Distance, Angle, CobbAngle, Arrow, Bidirectional, Ellipse };

const char* measurementKindName(MeasurementKind kind); // "Distance", "Cobb angle", ...
int measurementPointCount(MeasurementKind kind);

// What a measurement is in a RECIST 1.1 read: a target lesion (its diameter counts in the
// sum), a non-target lesion (followed, not summed) or neither. One lesion measured on
// several studies of a patient is one tracked lesion: the same trackingUid in each study's
// SR (DICOM's Tracking Unique Identifier); the measurement's label is its Tracking
// Identifier ("Liver 1").
enum class LesionRole { None, Target, NonTarget };
const char* lesionRoleName(LesionRole role); // "", "Target", "Non-target"

struct LesionTracking {
    LesionRole role = LesionRole::None;
    bool lymphNode = false;  // measured by its short axis
    std::string trackingUid; // a DICOM UID; empty: none given yet (the SR writer makes one)

    bool operator==(const LesionTracking&) const = default;
};

struct Measurement {
    std::uint64_t id = 0; // given by MeasurementDocument; unique within it
    MeasurementKind kind = MeasurementKind::Distance;
    std::string label; // the reader's name for it ("Lesion 1"); empty: none given
    std::string text;  // an arrow's annotation
    std::vector<glm::dvec3> points;
    // The plane it was drawn on: the slice (acquired or oblique) and its screen axes.
    SlicePlane plane;
    RoiStatistics statistics; // Ellipse only
    // Of the statistics: "HU" for CT, a PET series' unit ("SUVbw", "Bq/mL": PetDisplay::unit),
    // "" otherwise.
    std::string unit;
    // Ellipse on a PET series shown in SUVbw: SUVmax, SUVmean and SUVpeak over the ellipsoid
    // it spans (ellipseSuvRegion); read from an SR, the voxels are not known (maxVoxel and
    // peakVoxel -1, voxels 0).
    std::optional<SuvStatistics> suv;
    bool readOnly = false; // read from an SR that Lucent did not write
    LesionTracking lesion;

    bool complete() const { return static_cast<int>(points.size()) == measurementPointCount(kind); }
};

// The values a reader sees, from the points (mm and degrees).
double measurementLengthMm(const Measurement& m);     // Distance, Arrow: between the points
double measurementAngleDegrees(const Measurement& m); // Angle: at the vertex, 0..180;
                                                      // Cobb: between the lines, 0..90
double bidirectionalLongAxisMm(const Measurement& m);
double bidirectionalShortAxisMm(const Measurement& m);
EllipseRoi measurementEllipse(const Measurement& m); // Ellipse: centre and semi-axes

// An ellipse measurement from its centre and semi-axes along plane.u and plane.v.
Measurement makeEllipseMeasurement(const SlicePlane& plane, const EllipseRoi& ellipse);

// The text a list or an overlay shows for the value: "42.1 mm", "37.5°",
// "23.0 x 11.2 mm", "Mean 40.2 HU SD 3.1 Area 120.4 mm²", the arrow's text; an ellipse
// in SUVbw leads with "SUVmax 5.12 SUVpeak 4.20 SUVmean 2.51 ".
std::string measurementValueText(const Measurement& m);

// The unit an ellipse's statistics are in on this volume: "HU" for CT, the PET unit for a
// PET series loaded for display ("SUVbw", "Bq/mL"), "" otherwise.
std::string measurementUnit(const Volume& volume);

// An ellipse's SUVmax, SUVmean and SUVpeak on a volume shown in SUVbw (over
// ellipseSuvRegion); nothing for other kinds, incomplete ellipses and other volumes.
std::optional<SuvStatistics> measurementSuv(const Volume& volume, const Measurement& m);

// The largest distance of any point from the plane (mm): 0 for points drawn on it.
double distanceFromPlane(const Measurement& m, const SlicePlane& plane);

} // namespace lucent
