#pragma once

#include <optional>
#include <string>

#include "core/pet/PetDisplay.h"

namespace lucent {

// What a series is, for people, overlays and the study browser: the same facts
// for a header, a catalog entry and a loaded volume.
struct SeriesInfo {
    std::string seriesUid; // DICOM Series Instance UID; the file path for other formats
    std::string studyUid;
    std::string modality; // "CT", "MR", ...
    std::string description;
    std::string patientName;
    std::string patientId;
    std::string studyDate;
    // (0020,0052): series that share it share patient coordinates (linked views).
    std::string frameOfReferenceUid;
    // A PET series as loaded for display (loadDisplayedSeries): in SUVbw, or in its stored
    // units and why not; empty for other series and for what loadSeries alone returns.
    std::optional<PetDisplay> pet{};
};

// A DICOM date YYYYMMDD as YYYY-MM-DD, for people; anything else as it is.
std::string formatStudyDate(const std::string& dicomDate);

} // namespace lucent
