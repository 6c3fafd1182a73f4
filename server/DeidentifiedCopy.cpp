#include "server/DeidentifiedCopy.h"

#include <set>

#include "core/dicom/Deidentifier.h"
#include "core/io/Catalog.h"

namespace lucent::remote {

std::shared_ptr<const SeriesEntry> makeDeidentifiedCopy(const SeriesEntry& original,
                                                        const std::filesystem::path& storeDir) {
    if (original.format != SourceFormat::Dicom) {
        SeriesEntry alias = original;
        alias.id = generateUid();
        alias.seriesUid = alias.id;
        alias.studyUid.clear();
        alias.description.clear();
        alias.patientName.clear();
        alias.patientId.clear();
        alias.studyDate.clear();
        return std::make_shared<const SeriesEntry>(std::move(alias));
    }
    std::vector<std::filesystem::path> files;
    std::set<std::string> seen;
    for (const SliceRef& slice : original.slices) {
        if (seen.insert(slice.file).second) {
            files.emplace_back(slice.file);
        }
    }
    const std::filesystem::path destination = storeDir / "deidentified" / generateUid();
    deidentifySeries(files, destination);
    Catalog catalog = scanPath(destination);
    for (SeriesEntry& entry : catalog.series) {
        if (entry.kind == SeriesKind::Volume && entry.geometry.dims == original.geometry.dims) {
            return std::make_shared<const SeriesEntry>(std::move(entry));
        }
    }
    throw DeidentifyError("de-identify: the copy of the series does not load as the same volume");
}

} // namespace lucent::remote
