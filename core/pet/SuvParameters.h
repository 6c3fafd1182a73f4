#pragma once
// SUV body weight (SUVbw) from a PET series' header: what the factor needs and the
// factor itself, with the conditions QIBA's pseudo-code and cornerstonejs/calculate-suv
// apply. Plain C++ (lucent_core); readSuvParameters (core/dicom/PetSuvReader.h) fills it.

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace lucent {

// Why no SUVbw factor can be computed; the message names the DICOM element and what is
// wrong with it ("PatientWeight (0010,1030) is missing").
class SuvError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The elements SUVbw depends on, as read. Times are seconds since 1970-01-01 (no time
// zone); nullopt where the element is absent or not a valid DICOM date/time.
struct SuvParameters {
    std::string units;                     // Units (0054,1001): BQML, CNTS, GML, ...
    std::string correctedImage;            // CorrectedImage (0028,0051), backslash-separated
    std::string decayCorrection;           // DecayCorrection (0054,1102): START, ADMIN, NONE
    std::optional<double> patientWeightKg; // PatientWeight (0010,1030)
    std::optional<double> totalDoseBq;     // RadionuclideTotalDose (0018,1074)
    std::optional<double> halfLifeS;       // RadionuclideHalfLife (0018,1075)
    // RadiopharmaceuticalStartDateTime (0018,1078), else RadiopharmaceuticalStartTime
    // (0018,1072) on the SeriesDate.
    std::optional<double> injectionTime;
    std::optional<double> seriesTime;              // SeriesDate/SeriesTime (0008,0021/0031)
    std::optional<double> earliestAcquisitionTime; // AcquisitionDate/Time (0008,0022/0032)
};

// The time the decay is computed to: the series date and time, unless it lies after the
// earliest acquisition (post-processing may have rewritten it), then that acquisition.
// Throws SuvError when neither is known.
double suvScanReferenceTime(const SuvParameters& p);

// The factor that turns Bq/mL into SUVbw (g/mL):
//   weight [g] / (dose [Bq] * 2^(-dt / halfLife)), dt = scan reference - injection.
// Throws SuvError for Units other than BQML (CNTS, GML, ...), CorrectedImage without ATTN
// or DECY, DecayCorrection other than START, a missing or non-positive weight, dose or
// half-life, a missing injection or scan time and an injection after the scan reference.
double suvBwFactor(const SuvParameters& p);

// DICOM dates and times as seconds since 1970-01-01 (no time zone). DA "YYYYMMDD"
// (also "YYYY.MM.DD"), TM "HH[MM[SS[.F...]]]" (also "HH:MM:SS"), DT "YYYYMMDDHHMMSS.F..."
// with an optional "+HHMM"/"-HHMM" suffix that is ignored. nullopt when malformed.
std::optional<double> dicomDateTimeSeconds(std::string_view da, std::string_view tm);
std::optional<double> dicomDtSeconds(std::string_view dt);

} // namespace lucent
