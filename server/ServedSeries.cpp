#include "server/ServedSeries.h"

#include <set>

#include "core/io/Catalog.h"
#include "core/store/StudyStore.h"

namespace lucent::remote {
namespace {

void addVolumes(const std::filesystem::path& path, ServedSeries& served) {
    Catalog catalog = scanPath(path);
    served.skippedFiles += catalog.skipped.size();
    std::set<std::string> ids;
    for (const auto& s : served.volumes) {
        ids.insert(s->id);
    }
    for (SeriesEntry& entry : catalog.series) {
        if (entry.kind == SeriesKind::Volume && ids.insert(entry.id).second) {
            served.volumes.push_back(std::make_shared<const SeriesEntry>(std::move(entry)));
        }
    }
}

} // namespace

ServedSeries scanStoreSeries(const std::filesystem::path& storeRoot) {
    const StudyStore store(storeRoot);
    ServedSeries served;
    std::error_code error;
    if (std::filesystem::is_directory(store.root() / "files", error)) {
        addVolumes(store.root() / "files", served);
    }
    return served;
}

ServedSeries scanDataSeries(const std::filesystem::path& data) {
    ServedSeries served;
    addVolumes(data, served);
    return served;
}

SeriesList mergeServedSeries(const SeriesList& store, const SeriesList& data) {
    SeriesList merged = store;
    std::set<std::string> ids;
    for (const auto& s : store) {
        ids.insert(s->id);
    }
    for (const auto& s : data) {
        if (ids.insert(s->id).second) {
            merged.push_back(s);
        }
    }
    return merged;
}

ServedSeries scanServedSeries(const std::filesystem::path& storeRoot,
                              const std::optional<std::filesystem::path>& data) {
    ServedSeries served = scanStoreSeries(storeRoot);
    if (data) {
        const ServedSeries fromData = scanDataSeries(*data);
        served.volumes = mergeServedSeries(served.volumes, fromData.volumes);
        served.skippedFiles += fromData.skippedFiles;
    }
    return served;
}

} // namespace lucent::remote
