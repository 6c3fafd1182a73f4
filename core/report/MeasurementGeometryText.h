#pragma once
// A measurement's exact geometry as a line of text, for the private TEXT item of
// Lucent's SRs: kind, id, whether it has a label, points, plane, statistics, unit and
// SUVs (when it has them), every number with 17 significant digits (a double read back is
// the same).

#include <optional>
#include <string>

#include "core/measure/Measurement.h"

namespace lucent {

std::string encodeMeasurementGeometry(const Measurement& m);

// The measurement (label and text left empty; `labelled` says whether the tracking
// identifier is the reader's label) or nothing when the text is not one of ours.
struct DecodedGeometry {
    Measurement measurement;
    bool labelled = false;
};
std::optional<DecodedGeometry> decodeMeasurementGeometry(const std::string& text);

} // namespace lucent
