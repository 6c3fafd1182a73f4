#include "core/io/DisplayedSeries.h"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <vector>

#include "core/dicom/PetSuvReader.h"
#include "core/io/Catalog.h"
#include "core/pet/SuvStatistics.h"

namespace lucent {

namespace {

// Each file of the entry once, in slice order (a multi-frame file holds several slices).
std::vector<std::filesystem::path> filesOf(const SeriesEntry& entry) {
    std::vector<std::filesystem::path> files;
    for (const SliceRef& slice : entry.slices) {
        if (std::find(files.begin(), files.end(), slice.file) == files.end()) {
            files.emplace_back(slice.file);
        }
    }
    return files;
}

} // namespace

Volume loadDisplayedSeries(const SeriesEntry& entry, const LoadControl& control) {
    Volume volume = loadSeries(entry, control);
    if (entry.modality != "PT" || entry.format != SourceFormat::Dicom || entry.slices.empty()) {
        return volume;
    }
    if (control.stopRequested()) {
        throw LoadCancelled();
    }
    if (control.onProgress) {
        control.onProgress({"reading the SUV parameters", 0, 1});
    }
    SuvParameters parameters;
    try {
        parameters = readSuvParameters(filesOf(entry));
    } catch (const std::exception& e) {
        PetDisplay display;
        display.refusal = std::string("the SUV parameters could not be read: ") + e.what();
        volume.pet = display;
        return volume;
    }
    return petVolumeForDisplay(std::move(volume), parameters);
}

} // namespace lucent
