#pragma once
// What lucent-server offers its clients: the volumes of its study store
// (scanned at start and again when instances arrive) and of the --data path
// (scanned once at start).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/io/SeriesEntry.h"

namespace lucent::remote {

using SeriesList = std::vector<std::shared_ptr<const SeriesEntry>>;

struct ServedSeries {
    SeriesList volumes; // ids unique
    std::size_t skippedFiles = 0;
};

// Opens (or creates) the store at storeRoot and scans its files. Throws StoreError or LoadError.
ServedSeries scanStoreSeries(const std::filesystem::path& storeRoot);
// The volumes of a DICOM folder or volume file. Throws LoadError.
ServedSeries scanDataSeries(const std::filesystem::path& data);
// The store's series, then those of the data path whose ids the store lacks.
SeriesList mergeServedSeries(const SeriesList& store, const SeriesList& data);

// Both scans, merged.
ServedSeries scanServedSeries(const std::filesystem::path& storeRoot,
                              const std::optional<std::filesystem::path>& data);

} // namespace lucent::remote
