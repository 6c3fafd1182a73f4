#pragma once
// A PET series made from real CT files with DCMTK: the CT's pixels as stored values, a
// rescale slope per image, and the header elements SUVbw depends on, each settable or
// left out (an empty string leaves the element out), for tests of core/pet.

#include <filesystem>
#include <string>
#include <vector>

namespace lucent::test {

struct PetHeader {
    std::string units = "BQML";
    std::string correctedImage = "ATTN\\DECY";
    std::string decayCorrection = "START";
    std::string patientWeight = "75.5";  // kg
    std::string totalDose = "370000000"; // Bq
    std::string halfLife = "6586.2";     // s (18F)
    std::string startTime = "083000";    // RadiopharmaceuticalStartTime
    std::string startDateTime;           // RadiopharmaceuticalStartDateTime
    std::string seriesDate = "20150206";
    std::string seriesTime = "093500";
    std::string acquisitionDate = "20150206";
    double acquisitionStart = 9 * 3600 + 35 * 60; // of the first image, seconds after midnight
    double acquisitionStep = 30.0;                // later images, each this much later
    double slope = 0.5;      // RescaleSlope of the first image (intercept 0) ...
    double slopeStep = 0.25; // ... each later image's this much larger
};

struct PetSeries {
    std::string seriesUid;
    std::vector<std::filesystem::path> files; // in the order of the sorted CT file names
    std::vector<double> slopes;               // files[n]'s RescaleSlope
};

// Copies every DICOM file directly in `ctFolder` into `target` (created) as a PET image
// of one new series. Throws std::runtime_error naming the file on failure.
PetSeries writePetFromCt(const std::filesystem::path& ctFolder, const std::filesystem::path& target,
                         const PetHeader& header);

// The activity (Bq/mL) the series holds at pixel (i, j) of `file` (one of pet.files): its
// stored value (the CT's 12 bits, read with DCMTK) times that file's slope; NaN when the
// file is not one of the series or cannot be read.
double storedActivity(const PetSeries& pet, const std::filesystem::path& file, int i, int j);

} // namespace lucent::test
