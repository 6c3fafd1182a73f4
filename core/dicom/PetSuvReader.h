#pragma once
// Reading the SUV parameters of a PET series from its DICOM headers (GDCM, private to
// lucent_io); core/pet computes with them.

#include <filesystem>
#include <span>

#include "core/pet/SuvParameters.h"

namespace lucent {

// The parameters in one file's header; its own acquisition date and time count as the
// earliest. Elements that are absent stay empty (suvBwFactor says what is missing).
// Throws std::runtime_error naming the file when it is no readable DICOM file.
SuvParameters readSuvParameters(const std::filesystem::path& dicomFile);

// The parameters of a series: those of the first file, with the earliest acquisition date
// and time over all of them (what QIBA compares the series time against).
SuvParameters readSuvParameters(std::span<const std::filesystem::path> seriesFiles);

} // namespace lucent
