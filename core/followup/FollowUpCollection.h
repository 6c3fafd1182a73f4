#pragma once
// The measurements of one patient's studies in the local study store, gathered into
// timepoints for the RECIST table (core/followup/Recist.h): every image series of the
// patient that an SR of the store refers to, read through MeasurementArchive (Lucent's SRs
// and other tools' alike), grouped by study date.

#include <string>
#include <vector>

#include "core/followup/Recist.h"
#include "core/report/MeasurementArchive.h"
#include "core/store/StudyStore.h"

namespace lucent {

struct FollowUpSources {
    std::string patientId;
    std::string patientName;
    std::vector<TimepointMeasurements> timepoints; // one per study date, in date order
    std::vector<std::string> problems; // series whose measurements could not be read, why
};

// Throws StoreError naming the store when it holds no series of the patient. `archive` (of
// `store`) keeps the image headers it read: a panel that refreshes keeps one.
FollowUpSources collectFollowUp(StudyStore& store, MeasurementArchive& archive,
                                const std::string& patientId);
FollowUpSources collectFollowUp(StudyStore& store, const std::string& patientId);

// The study date (YYYYMMDD) of an indexed series; "" when unknown.
std::string studyDateOf(const StudyStore& store, const std::string& seriesUid);

} // namespace lucent
