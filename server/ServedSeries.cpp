#include "server/ServedSeries.h"

#include <set>

#include "core/io/Catalog.h"
#include "core/store/StudyStore.h"

namespace lucent::remote {

ServedSeries scanServedSeries(const std::filesystem::path& storeRoot,
                              const std::optional<std::filesystem::path>& data) {
    const StudyStore store(storeRoot);
    std::vector<std::filesystem::path> paths;
    std::error_code error;
    if (std::filesystem::is_directory(store.root() / "files", error)) {
        paths.push_back(store.root() / "files");
    }
    if (data) {
        paths.push_back(*data);
    }
    ServedSeries served;
    std::set<std::string> ids;
    for (const auto& path : paths) {
        Catalog catalog = scanPath(path);
        served.skippedFiles += catalog.skipped.size();
        for (SeriesEntry& entry : catalog.series) {
            if (entry.kind == SeriesKind::Volume && ids.insert(entry.id).second) {
                served.volumes.push_back(std::make_shared<const SeriesEntry>(std::move(entry)));
            }
        }
    }
    return served;
}

} // namespace lucent::remote
