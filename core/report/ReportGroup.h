#pragma once
// What one Measurement Group of an SR holds, read out of DCMTK's tree into plain
// types, and the measurement Lucent makes of it. Plain C++ (no DCMTK): the
// reader fills it, interpretGroup() decides.

#include <optional>
#include <string>
#include <vector>

#include "core/measure/Measurement.h"

namespace lucent {

struct ReportRegion {
    enum class Shape { Point, Polyline, Polygon, Ellipse, Circle, Multipoint, Other };
    Shape shape = Shape::Other;
    std::vector<glm::dvec3> points;       // patient mm; empty when it could not be placed
    std::optional<SlicePlane> imagePlane; // for a SCOORD: the plane of its image
    std::string unplaced; // why it could not be placed (e.g. an image not in the series)
};

struct ReportNumber {
    std::string code;   // "410668003"
    std::string scheme; // "SCT"
    std::string meaning;
    double value = 0.0;
    std::string unit;       // UCUM code
    std::string derivation; // the code of its Derivation (121401, DCM), "" when none
    std::optional<ReportRegion> region;
};

struct ReportGroup {
    std::string trackingIdentifier;
    // Tracking Unique Identifier, RECIST category (Baseline Category), lymph node (Finding Site).
    LesionTracking lesion;
    std::vector<ReportNumber> numbers;
    std::optional<std::string> comment;  // TEXT (121106, DCM, "Comment")
    std::optional<std::string> geometry; // Lucent's private TEXT item
    std::vector<std::string> otherItems; // items of no meaning to Lucent, in words
};

struct InterpretedGroup {
    std::optional<Measurement> measurement;
    std::vector<std::string> notShown; // what of the group could not be shown, in words
};

// The measurement of a group: exact from Lucent's geometry item when present, else
// from its numbers and regions (readOnly). `lucentWrote`: the SR's Manufacturer.
InterpretedGroup interpretGroup(const ReportGroup& group, bool lucentWrote);

} // namespace lucent
