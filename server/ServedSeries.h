#pragma once
// What lucent-server offers its clients: the volumes of its study store and
// of the --data path, scanned once at start.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/io/SeriesEntry.h"

namespace lucent::remote {

struct ServedSeries {
    std::vector<std::shared_ptr<const SeriesEntry>> volumes; // ids unique
    std::size_t skippedFiles = 0;
};

// Opens (or creates) the store at storeRoot and scans its files and, when
// given, the data path. Throws StoreError or LoadError.
ServedSeries scanServedSeries(const std::filesystem::path& storeRoot,
                              const std::optional<std::filesystem::path>& data);

} // namespace lucent::remote
