#pragma once
// How the workstation shows a PET series' values: in SUVbw (the factor applied when the
// series was loaded) or, when no factor can be computed, in the stored units with the
// reason. It is kept with the loaded volume (SeriesInfo::pet), so the views, the
// measurements and the fusion overlays ask one place whether a series is in SUV and in what
// unit. Plain C++ (lucent_core); light on purpose, as every volume carries it.

#include <string>

namespace lucent {

struct SuvParameters;

struct PetDisplay {
    // SUVbw per stored unit (g/mL per Bq/mL), applied to the voxels when loading; 1 for
    // Units GML (already SUVbw); 0 when the voxels hold the stored units.
    double suvFactor = 0.0;
    std::string storedUnits; // Units (0054,1001) as stored: BQML, CNTS, GML, ...; "" absent
    // Why the values are not in SUVbw: SuvError's message, which names the element
    // ("PatientWeight (0010,1030) is missing"); empty when they are.
    std::string refusal;

    bool inSuv() const { return suvFactor > 0.0; }
    // What the values are in, for people: "SUVbw"; else the stored unit: "Bq/mL" (BQML),
    // "counts" (CNTS), Units as stored otherwise, "" when absent.
    std::string unit() const;
    // The same as a UCUM code, as DICOM SR writes measurement units: "{SUVbw}g/ml",
    // "Bq/ml", "{counts}", "{<Units>}" for other stored units, "1" (no units) when absent.
    std::string ucum() const;

    bool operator==(const PetDisplay&) const = default;
};

// The display of a series with these parameters: SUVbw with suvBwFactor's factor; Units
// GML as SUVbw as stored (factor 1); else the stored units with suvBwFactor's refusal.
PetDisplay petDisplayOf(const SuvParameters& parameters);

// What the user is told once when a PET series cannot be shown in SUVbw ("PT series shown
// in Bq/mL, not in SUVbw: PatientWeight (0010,1030) is missing"); "" when it is in SUVbw.
std::string petDisplayNotice(const PetDisplay& display);

// The window a PET series in SUVbw opens with: 0 to 6 SUV (what the liver, about 2, and the
// blood pool sit well inside and lesions saturate towards), 0.01 SUV per pixel of drag.
inline constexpr double kSuvWindowLow = 0.0;
inline constexpr double kSuvWindowHigh = 6.0;
inline constexpr double kSuvWindowStep = 0.01;

} // namespace lucent
