#include "core/followup/FollowUpCollection.h"

#include <algorithm>
#include <map>
#include <set>

#include "core/report/MeasurementArchive.h"
#include "core/report/MeasurementReport.h"

namespace lucent {

std::string studyDateOf(const StudyStore& store, const std::string& seriesUid) {
    for (const StoredSeries& s : store.listSeries()) {
        if (s.info.seriesUid == seriesUid) {
            return s.info.studyDate;
        }
    }
    return {};
}

FollowUpSources collectFollowUp(StudyStore& store, const std::string& patientId) {
    MeasurementArchive archive(store);
    return collectFollowUp(store, archive, patientId);
}

FollowUpSources collectFollowUp(StudyStore& store, MeasurementArchive& archive,
                                const std::string& patientId) {
    FollowUpSources out;
    out.patientId = patientId;
    std::map<std::string, const StoredSeries*> images; // the patient's image series by UID
    std::vector<const StoredSeries*> reports;
    const std::vector<StoredSeries> all = store.listSeries();
    for (const StoredSeries& s : all) {
        if (s.info.patientId != patientId) {
            continue;
        }
        out.patientName = s.info.patientName;
        if (s.info.modality == "SR") {
            reports.push_back(&s);
        } else {
            images[s.info.seriesUid] = &s;
        }
    }
    if (reports.empty() && images.empty()) {
        throw StoreError(store.root().string() + ": no series of patient '" + patientId + "'");
    }
    // The image series the patient's SRs refer to.
    std::set<std::string> measured;
    for (const StoredSeries* sr : reports) {
        for (const auto& [sop, file] : store.instanceFiles(sr->info.seriesUid)) {
            try {
                for (const std::string& uid : readMeasurementReport(file).referencedSeries) {
                    if (images.count(uid) != 0) {
                        measured.insert(uid);
                    }
                }
            } catch (const ReportError&) {
                // Not a measurement report (a dose report, a key object): nothing to follow.
            }
        }
    }
    std::map<std::string, TimepointMeasurements> byDate;
    for (const std::string& uid : measured) {
        const SeriesInfo& info = images.at(uid)->info;
        // Studies without a date are timepoints of their own, after the dated ones.
        const std::string key = info.studyDate.empty() ? "~" + info.studyUid : info.studyDate;
        TimepointMeasurements& t = byDate[key];
        t.studyDate = info.studyDate;
        if (std::find(t.studyUids.begin(), t.studyUids.end(), info.studyUid) == t.studyUids.end()) {
            t.studyUids.push_back(info.studyUid);
        }
        try {
            const LesionLocation where{info.studyDate, info.studyUid, uid, glm::dvec3(0.0)};
            for (const Measurement& m : archive.load(uid).measurements) {
                if (auto o = lesionObservationOf(m, where)) {
                    t.lesions.push_back(std::move(*o));
                }
            }
        } catch (const std::exception& e) {
            out.problems.push_back(std::string("series ") + uid + ": " + e.what());
        }
    }
    for (auto& [key, t] : byDate) {
        out.timepoints.push_back(std::move(t));
    }
    return out;
}

} // namespace lucent
