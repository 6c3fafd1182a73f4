#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/pacs/PacsNode.h"

namespace lucent {

enum class QueryLevel { Patient, Study, Series };
const char* queryLevelName(QueryLevel level);
QueryLevel parseQueryLevel(std::string_view name); // throws PacsError

// C-FIND filters; empty ones match everything. Patient names take DICOM
// wildcards (* and ?). dateRange is a DICOM range: YYYYMMDD, YYYYMMDD-YYYYMMDD,
// YYYYMMDD- or -YYYYMMDD. Several modalities match any of them.
struct QueryFilter {
    std::string patientName;
    std::string patientId;
    std::string accessionNumber;
    std::string studyUid;
    std::string dateRange;
    std::vector<std::string> modalities;

    // Throws PacsError naming the filter that is malformed.
    void validate() const;
};

struct QueryMatch {
    QueryLevel level = QueryLevel::Study;
    std::string patientName;
    std::string patientId;
    std::string patientBirthDate;
    std::string studyUid;
    std::string studyDate;
    std::string studyTime;
    std::string studyDescription;
    std::string accessionNumber;
    std::string modalitiesInStudy;
    std::string seriesUid;
    std::string seriesDescription;
    std::string modality;
    std::string bodyPart; // BodyPartExamined, series level
    int seriesNumber = 0;
    int instances = 0; // in the study (study level) or series (series level)
};

// C-ECHO. Throws PacsError naming the node and the cause.
void echo(const PacsNode& node, const PacsSettings& settings);

// C-FIND at a level, with the filters. At series level without a study UID,
// the matching studies are found first and their series listed. Results are
// de-duplicated by UID and sorted by date, then UID.
std::vector<QueryMatch> find(const PacsNode& node, const PacsSettings& settings, QueryLevel level,
                             const QueryFilter& filter);

// Matches keyed by UID, as a list sorted by study date, study UID, series number.
std::vector<QueryMatch> orderedMatches(std::map<std::string, QueryMatch> unique);

} // namespace lucent
