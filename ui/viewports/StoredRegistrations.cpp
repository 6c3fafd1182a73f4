#include "ui/viewports/StoredRegistrations.h"

#include <algorithm>

#include "core/store/StudyStore.h"

namespace lucent {

void StoredRegistrations::clear() {
    registrations_.clear();
    problems_.clear();
}

void StoredRegistrations::load(const StudyStore& store) {
    clear();
    std::vector<StoredSeries> series = store.listSeries();
    std::reverse(series.begin(), series.end());
    for (const StoredSeries& s : series) {
        if (s.info.modality != "REG") {
            continue;
        }
        for (const auto& [sop, file] : store.instanceFiles(s.info.seriesUid)) {
            try {
                registrations_.push_back(readSpatialRegistration(file));
            } catch (const std::exception& e) {
                problems_.push_back(e.what());
            }
        }
    }
}

std::optional<glm::dmat4> StoredRegistrations::between(const std::string& frameA,
                                                       const std::string& frameB) const {
    if (frameA.empty() || frameB.empty() || frameA == frameB) {
        return std::nullopt;
    }
    for (const SpatialRegistration& r : registrations_) {
        if (auto t = frameTransform(r, frameA, frameB)) {
            return t;
        }
    }
    return std::nullopt;
}

} // namespace lucent
